"""The bad-input contract (docs/formats.md): every case of tests/bad_inputs/manifest.json
runs the built tool and must exit 1, name the file (and the line or element) or the flag
in its message, and leave no output behind. Run by ctest with STRICTMIN_CLI pointing at
the built tool.

A case marked "needs": "X" runs only when STRICTMIN_EXPECT_X=1 (X upper-cased, '-' as
'_'): it states a contract that a change in progress brings (e.g. option validation)."""
import json
import os
import sys
import tempfile
import unittest
from concurrent.futures import ThreadPoolExecutor

from cli_support import run

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "bad_inputs")
MANIFEST = os.path.join(CORPUS, "manifest.json")

# Output flags added to every case (unless it gives the flag itself), all in {out}.
OUTPUTS = {
    "deform": {"-o": "out.obj", "--summary": "summary.json", "--distortion": "distortion.txt", "--report": "report"},
    "param": {"-o": "out.obj", "--summary": "summary.json", "--distortion": "distortion.txt", "--report": "report"},
    "eval": {"-o": "out.ply", "--summary": "summary.json", "--distortion": "distortion.txt", "--report": "report"},
    "interp": {"-o": "frame", "--summary": "summary.json", "--distortion": "distortion.txt", "--report": "report"},
}


def load_cases():
    with open(MANIFEST) as f:
        return json.load(f)["cases"]


def expected(needs):
    return os.environ.get("STRICTMIN_EXPECT_" + needs.upper().replace("-", "_")) == "1"


def command_line(case, out):
    args = [a.replace("{dir}", CORPUS).replace("{out}", out) for a in case["args"]]
    for flag, name in OUTPUTS.get(args[0], {}).items():
        if flag not in args:
            args += [flag, os.path.join(out, name)]
    return args


def run_case(case):
    """Runs one case in a fresh temporary folder; returns (args, process, files left)."""
    with tempfile.TemporaryDirectory() as out:
        args = command_line(case, out)
        p = run(*args, timeout=120)
        left = sorted(os.listdir(out))
    return args, p, left


class BadInputs(unittest.TestCase):
    def test_manifest(self):
        cases = load_cases()
        self.assertGreaterEqual(len(cases), 40)
        ids = [c["id"] for c in cases]
        self.assertEqual(len(ids), len(set(ids)), "case ids are unique")
        used = set()
        for c in cases:
            with self.subTest(case=c["id"]):
                self.assertEqual(c["exit"], 1)
                self.assertTrue(c["message"], "every case names what the message must contain")
                # The message must name the input: a file of the command line, a flag or the
                # value given to it.
                names = {os.path.basename(a) for a in c["args"]} | set(c["args"])
                self.assertTrue(names & set(c["message"]), "no file, flag or value among the substrings")
                for a in c["args"]:
                    if a.startswith("{dir}/"):
                        used.add(a[len("{dir}/"):])
        # Every file of the corpus is used by some case; every case's file exists unless it
        # is the missing-file case.
        files = set(os.listdir(CORPUS)) - {"manifest.json"}
        self.assertEqual(sorted(files - used), [], "corpus files no case uses")
        self.assertEqual(sorted(used - files), ["no_such_file.obj", "no_such_handles.txt"])

    def test_every_case_exits_1_names_the_input_and_writes_nothing(self):
        cases = load_cases()
        active = [c for c in cases if "needs" not in c or expected(c["needs"])]
        skipped = [c for c in cases if c not in active]
        with ThreadPoolExecutor(max_workers=4) as pool:
            results = list(pool.map(run_case, active))
        for case, (args, p, left) in zip(active, results):
            with self.subTest(case=case["id"]):
                where = f"{case['id']}: strictmin {' '.join(args)}\nstderr: {p.stderr[-2000:]}"
                self.assertEqual(p.returncode, case["exit"], where)
                for needle in case["message"]:
                    self.assertIn(needle, p.stderr, where)
                self.assertEqual(left, [], "output left behind: " + where)
        by_need = {}
        for c in skipped:
            by_need.setdefault(c["needs"], []).append(c["id"])
        for need, ids in sorted(by_need.items()):
            var = "STRICTMIN_EXPECT_" + need.upper().replace("-", "_")
            print(f"bad inputs: {len(ids)} case(s) skipped, they need {need} (set {var}=1): {', '.join(ids)}",
                  file=sys.stderr)
        print(f"bad inputs: {len(active)} case(s) run, {len(skipped)} skipped", file=sys.stderr)


if __name__ == "__main__":
    result = unittest.main(exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
