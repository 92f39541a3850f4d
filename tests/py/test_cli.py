"""End-to-end tests of the strictmin command line: summaries, outputs, exit codes and the
messages for bad input. Run by ctest with STRICTMIN_CLI pointing at the built tool."""
import json
import signal
import math
import os
import subprocess
import sys
import tempfile
import unittest

from cli_support import CLI, DATA, run, write


SUMMARY_KEYS = {"task", "version", "method", "measure", "elements", "max_distortion", "l2_distortion", "flipped", "status", "time_s"}


class Deform(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_square_l2_summary_on_stdout(self):
        p = run("deform", "--example", "square", "--method", "l2", "--summary", "-", "--quiet", check_code=0)
        s = json.loads(p.stdout)
        self.assertTrue(SUMMARY_KEYS <= s.keys(), s.keys())
        self.assertEqual(s["task"], "deform")
        self.assertEqual(s["method"], "l2")
        self.assertEqual(s["measure"], "fd")
        self.assertEqual(s["elements"], 800)
        self.assertEqual(s["status"], "solved")
        self.assertGreater(s["max_distortion"], s["l2_distortion"])
        self.assertEqual(p.stderr, "", "--quiet prints nothing")

    def test_version_is_the_summarys(self):
        # One version (CMake's project(), strictmin/version.h): --version and every summary agree;
        # the consumer_package test checks it against CMake's.
        version = run("--version", check_code=0).stdout.strip()
        self.assertRegex(version, r"^strictmin \d+\.\d+\.\d+$")
        p = run("deform", "--example", "square", "--method", "l2", "--summary", "-", "--quiet", check_code=0)
        self.assertEqual("strictmin " + json.loads(p.stdout)["version"], version)
        mesh = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "consumer", "strip.obj")
        summary = os.path.join(self.dir, "eval.json")
        run("eval", mesh, mesh, "--summary", summary, "--quiet", check_code=0)
        with open(summary) as f:
            self.assertEqual("strictmin " + json.load(f)["version"], version)

    def test_square_direct_summary_levels_and_worst_level_gap(self):
        p = run("deform", "--example", "square", "--method", "direct", "--summary", "-", "--quiet", check_code=0)
        s = json.loads(p.stdout)
        self.assertEqual(s["status"], "solved")
        self.assertGreaterEqual(s["levels"], 2)
        # Paper Figure 2: the top level is 0.3; the levels after it stop at delta-k / 100.
        self.assertAlmostEqual(s["max_distortion"], 0.3, delta=1e-6)
        self.assertLessEqual(s["lower_bound"], s["max_distortion"])
        # Levels after the first stop at delta-k / 100 = 1e-5 (--level-gap), none stalls here.
        self.assertLessEqual(s["worst_level_gap"], 1e-5)

    def test_direct_level_cap_and_pinning_switch(self):
        # --max-levels stops direct with elements still free above k-min: max-iterations, exit 2.
        p = run("deform", "--example", "square", "--method", "direct", "--max-levels", "2", "--summary", "-",
                "--quiet", check_code=2)
        s = json.loads(p.stdout)
        self.assertEqual((s["status"], s["levels"], s["usable"]), ("max-iterations", 2, True))
        self.assertIn("level cap (2)", s["stop_reason"])
        # Pinned or not, the first level is the L-infinity optimum (Figure 2: 0.3) and both
        # end solved; the progress lines count the pinned elements.
        pinned = run("deform", "--example", "square", "--method", "direct", "--summary", "-", check_code=0)
        plain = run("deform", "--example", "square", "--method", "direct", "--no-pin", "--summary", "-",
                    check_code=0)
        self.assertIn("pinned", pinned.stderr)
        self.assertNotIn("pinned", plain.stderr)
        self.assertRegex(json.loads(pinned.stdout)["stop_reason"], r"\(\d+ elements pinned\)")
        self.assertNotIn("pinned", json.loads(plain.stdout)["stop_reason"])
        for q in (pinned, plain):
            s = json.loads(q.stdout)
            self.assertEqual(s["status"], "solved")
            self.assertAlmostEqual(s["max_distortion"], 0.3, delta=1e-6)

    def test_outputs_and_distortion_file(self):
        out = os.path.join(self.dir, "bar.ply")
        dist = os.path.join(self.dir, "bar.txt")
        summ = os.path.join(self.dir, "bar.json")
        run("deform", "--example", "bar", "-o", out, "--distortion", dist, "--summary", summ, check_code=0)
        values = [float(x) for x in open(dist).read().split()]
        s = json.load(open(summ))
        self.assertEqual(len(values), s["elements"])
        self.assertAlmostEqual(max(values), s["max_distortion"], places=12)
        ply = open(out).read()
        self.assertIn("property float quality", ply)
        self.assertEqual([f for f in os.listdir(self.dir) if f.startswith(".")], [], "no temporary files left")

    def test_mesh_file_and_text_handles(self):
        mesh = write(os.path.join(self.dir, "quad.obj"),
                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\n"
                     "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n")
        # Handles from the affine map x -> 2x: the interior vertex follows, every J = 2I.
        handles = write(os.path.join(self.dir, "h.txt"), "# corners\n0 0 0\n1 2 0\n2 2 2\n3 0 2\n")
        out = os.path.join(self.dir, "out.obj")
        p = run("deform", mesh, "--handles", handles, "-o", out, "--summary", "-", "-q", check_code=0)
        s = json.loads(p.stdout)
        self.assertAlmostEqual(s["max_distortion"], math.sqrt(2), places=10)
        self.assertAlmostEqual(s["l2_distortion"], math.sqrt(2), places=10)
        centre = [l for l in open(out) if l.startswith("v ")][4].split()
        self.assertAlmostEqual(float(centre[1]), 1.0, places=10)
        self.assertAlmostEqual(float(centre[2]), 1.0, places=10)

    def test_json_handles_and_tets(self):
        p = run("deform", "--example", "tetbar", "--summary", "-", "-q", check_code=0)
        s = json.loads(p.stdout)
        self.assertEqual(s["dimension"], 3)
        self.assertEqual(s["elements"], 16 * 4 * 4 * 6)

    def test_bad_inputs_exit_1_with_a_message(self):
        mesh = write(os.path.join(self.dir, "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        cases = [
            (["deform", os.path.join(self.dir, "missing.obj"), "--handles", mesh], "missing.obj"),
            (["deform", write(os.path.join(self.dir, "empty.obj"), ""), "--handles", mesh], "empty"),
            (["deform", write(os.path.join(self.dir, "x.stl"), "solid"), "--handles", mesh], ".stl"),
            (["deform", mesh, "--handles", write(os.path.join(self.dir, "h1.txt"), "7 0 0\n")], "7"),
            (["deform", mesh, "--handles", write(os.path.join(self.dir, "h2.txt"), "0 0 0\n0 1 1\n")], "0"),
            (["deform", mesh, "--handles", write(os.path.join(self.dir, "h3.txt"), "0 0 0 0\n")], "coordinates"),
            (["deform", mesh, "--handles", write(os.path.join(self.dir, "h4.json"), "{\"handles\": [}")], "h4.json"),
            (["deform", "--example", "square", "--method", "magic"], "magic"),
            (["deform", "--example", "nothing"], "nothing"),
            (["eval", mesh, write(os.path.join(self.dir, "two.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n")], "element"),
            (["eval", mesh], "vt"),
        ]
        for args, needle in cases:
            with self.subTest(args=args):
                p = run(*args)
                self.assertEqual(p.returncode, 1, p.stderr)
                self.assertIn("error", p.stderr)
                self.assertIn(needle, p.stderr)

    def test_outputs_that_would_overwrite_each_other_are_refused_first(self):
        # Two flags naming one file (the JSON replaced the mesh), and a --report that is a file
        # (the run wrote its other outputs and then failed): exit 1 before any work, nothing written.
        out = os.path.join(self.dir, "o.obj")
        p = run("deform", "--example", "square", "-o", out, "--summary", out, check_code=1)
        self.assertIn("--output writes the same file", p.stderr)
        p = run("deform", "--example", "square", "-o", out, "--distortion", os.path.join(self.dir, ".", "o.obj"),
                check_code=1)
        self.assertIn("--distortion", p.stderr)
        afile = write(os.path.join(self.dir, "afile"), "x")
        summary = os.path.join(self.dir, "s.json")
        p = run("deform", "--example", "square", "-o", out, "--summary", summary, "--report", afile, check_code=1)
        self.assertIn("--report", p.stderr)
        self.assertIn("is a file, not a folder", p.stderr)
        self.assertFalse(os.path.exists(out) or os.path.exists(summary))

    def test_an_output_that_names_an_input_is_refused_and_the_input_kept(self):
        # --summary mesh.obj replaced the input mesh with JSON (exit 0); the same for every
        # output flag of every task, through another spelling of the path or a hard link.
        square = "v 0 0\nv 1 0\nv 1 1\nv 0 1\nv 0.5 0.5\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"
        mesh = write(os.path.join(self.dir, "m.obj"), square)
        handles = write(os.path.join(self.dir, "h.txt"), "0 0 0\n2 1.2 1\n")
        target = write(os.path.join(self.dir, "m_1.obj"), square)
        link = os.path.join(self.dir, "link.obj")
        os.link(mesh, link)
        cases = [
            (["deform", mesh, "--handles", handles, "--summary", mesh], "--summary", "the input mesh"),
            (["deform", mesh, "--handles", handles, "-o", os.path.join(self.dir, ".", "m.obj")], "--output",
             "the input mesh"),
            (["deform", mesh, "--handles", handles, "--distortion", handles], "--distortion", "the --handles file"),
            (["deform", mesh, "--handles", handles, "-o", link], "--output", "the input mesh"),
            (["eval", mesh, target, "--summary", target], "--summary", "the mapped mesh"),
            (["interp", mesh, target, "--t", "0.5,1", "-o", os.path.join(self.dir, "m")], "--output", "the target pose"),
        ]
        for args, flag, what in cases:
            with self.subTest(args=args):
                p = run(*args, check_code=1)
                self.assertIn(flag, p.stderr)
                self.assertIn("is " + what, p.stderr)
                for path in (mesh, target):
                    with open(path) as f:
                        self.assertEqual(f.read(), square)
                with open(handles) as f:
                    self.assertEqual(f.read(), "0 0 0\n2 1.2 1\n")

    def test_every_solve_says_why_it_stopped(self):
        # stop_reason is never empty (it was for l2, exact and param's starting maps).
        for args in (["deform", "--example", "square", "--method", "l2"],
                     ["deform", "--example", "square", "--method", "exact"]):
            s = json.loads(run(*args, "--summary", "-", "--quiet", check_code=0).stdout)
            self.assertTrue(s["stop_reason"], args)
            self.assertEqual(s["message"], s["stop_reason"])

    def test_mistyped_command_or_option_is_named(self):
        # (CLI11 said "A subcommand is required" to both.)
        self.assertIn("unknown command 'defrom'", run("defrom", "--example", "square", check_code=1).stderr)
        self.assertIn("unknown option '--bogus'", run("--bogus", check_code=1).stderr)

    def test_ctrl_c_stops_the_solve_and_writes_nothing(self):
        # Ctrl-C (SIGINT) during direct's levels: exit 130 at the next level, no output file or
        # temporary left (the signal killed the process before, with no message).
        n = 60
        lines = [f"v {i} {j} 0" for j in range(n + 1) for i in range(n + 1)]
        for j in range(n):
            for i in range(n):
                a = j * (n + 1) + i + 1
                lines += [f"f {a} {a + 1} {a + n + 2}", f"f {a} {a + n + 2} {a + n + 1}"]
        mesh = write(os.path.join(self.dir, "grid.obj"), "\n".join(lines) + "\n")
        handles = [f"{j * (n + 1)} 0 {j}" for j in range(n + 1)] + \
                  [f"{j * (n + 1) + n} {n + 0.4 * n * math.sin(j / 7)} {j}" for j in range(n + 1)]
        h = write(os.path.join(self.dir, "h.txt"), "\n".join(handles) + "\n")
        out, summary = os.path.join(self.dir, "o.obj"), os.path.join(self.dir, "s.json")
        p = subprocess.Popen([CLI, "deform", mesh, "--handles", h, "--method", "direct", "--k-min", "0", "-o", out,
                              "--summary", summary], stderr=subprocess.PIPE, text=True)
        for line in p.stderr:  # the levels have started
            if "strict step   2" in line:
                break
        p.send_signal(signal.SIGINT)
        rest = p.stderr.read()
        self.assertEqual(p.wait(timeout=60), 130, rest[-2000:])
        self.assertIn("interrupted", rest)
        self.assertEqual(sorted(os.listdir(self.dir)), ["grid.obj", "h.txt"])

    def test_readmes_homer_handles(self):
        # README's 3D surface example: the script that writes its handles, then the deformation.
        homer = os.path.join(DATA, "closed", "homer.obj")
        if not os.path.exists(homer):
            self.skipTest("no shared data")
        script = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "python", "homer_handles.py")
        text = subprocess.run([sys.executable, script, homer], capture_output=True, text=True, check=True).stdout
        lines = text.split("\n")[:-1]
        self.assertGreater(len(lines), 100)
        self.assertTrue(all(len(l.split()) == 4 for l in lines))
        handles = write(os.path.join(self.dir, "homer_handles.txt"), text)
        s = json.loads(run("deform", homer, "--handles", handles, "--method", "l2", "--summary", "-", "--quiet",
                           check_code=0).stdout)
        self.assertEqual(s["handles"], len(lines))

    def test_handle_targets_beyond_the_sizes_are_refused(self):
        # (a target at 1e200 overflowed every distortion to inf, and l2 said solved)
        mesh = write(os.path.join(self.dir, "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
        handles = write(os.path.join(self.dir, "far.txt"), "0 1e200 0\n1 1 0\n")
        p = run("deform", mesh, "--handles", handles, check_code=1)
        # named with its file and line, as the handle files' other errors are
        self.assertIn("far.txt: line 1: handle for vertex 0 has the coordinate 1e+200, beyond 1e150", p.stderr)

    def test_flags_of_another_method_are_refused(self):
        # They were ignored without a word (--frame-iterations and --start were already refused).
        for args, needle in ((["--method", "linf", "--sweeps", "3"], "--sweeps applies to --method relax; --method linf"),
                             (["--method", "l2", "--linf-min-l2"], "--linf-min-l2 applies to --method linf"),
                             (["--method", "linf", "--p", "8"], "--p applies to --method lp (or relax starting from lp)"),
                             (["--method", "relax", "--delta-k", "0.01"], "--delta-k applies to --method direct"),
                             (["--method", "l2", "--no-pin"], "--no-pin applies to --method direct or exact"),
                             (["--report-scale", "2"], "--report-scale requires --report")):
            p = run("deform", "--example", "square", *args, "--summary", os.path.join(self.dir, "s.json"), check_code=1)
            self.assertIn(needle, p.stderr, args)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "s.json")), args)
        # relax reads the flags of the method it starts from.
        run("deform", "--example", "square", "--method", "relax", "--init", "lp", "--p", "8", "--sweeps", "1",
            "--quiet", check_code=0)

    def test_unknown_output_format_is_refused_before_the_solve(self):
        p = run("deform", "--example", "square", "-o", os.path.join(self.dir, "x.stl"), check_code=1)
        self.assertIn("unknown mesh format '.stl'", p.stderr)
        self.assertNotIn("deform:", p.stderr)  # no progress line: nothing was solved

    def test_report_address_is_percent_encoded(self):
        folder = os.path.join(self.dir, "R x#y%")
        p = run("deform", "--example", "square", "--method", "l2", "--report", folder, check_code=0)
        self.assertIn("R%20x%23y%25/index.html", p.stderr)

    def test_exact_with_arap_is_refused(self):
        out = os.path.join(self.dir, "x.obj")
        p = run("deform", "--example", "bar", "--method", "exact", "--measure", "arap", "-o", out, check_code=1)
        # The message names the flags (it said "the exact strict minimizer is for field deviation only").
        self.assertIn("--method exact (the exact strict minimizer) is for --measure fd only", p.stderr)
        self.assertFalse(os.path.exists(out))

    def test_exact_size_limit_names_its_flag(self):
        # The limit is --exact-max-elements: the message only said "use --method direct or relax".
        p = run("deform", "--example", "square", "--method", "exact", "--exact-max-elements", "10", check_code=1)
        self.assertIn("800 elements is above its limit of 10 (ExactOptions::max_elements: --exact-max-elements on the "
                      "command line, exact_max_elements in Python;", p.stderr)

    def test_local_global_flags_need_a_local_global_measure(self):
        # --lg-* with fd, qc or iso were accepted and ignored (no local steps to cap or tune);
        # they are refused by name, and with arap / asap they still apply.
        out = os.path.join(self.dir, "lg.obj")
        for flag in (["--lg-iterations", "5"], ["--lg-tolerance", "0.1"], ["--lg-acceleration", "0"],
                     ["--lg-extrapolation", "0"], ["--lg-cold-start"]):
            p = run("deform", "--example", "square", *flag, "-o", out, check_code=1)
            self.assertIn(flag[0] + " applies to --measure arap or asap", p.stderr)
            self.assertIn("not fd", p.stderr)
            self.assertFalse(os.path.exists(out))
        p = run("deform", "--example", "square", "--measure", "qc", "--lg-iterations", "5", "-o", out, check_code=1)
        self.assertIn("--lg-iterations applies to --measure arap or asap (their local-global iterations), not qc",
                      p.stderr)
        run("deform", "--example", "bar", "--measure", "asap", "--method", "l2", "--lg-iterations", "2", "-o", out,
            "--quiet", check_code=2)  # the cap reached: usable, not converged
        self.assertTrue(os.path.exists(out))

    def test_failed_run_leaves_no_output(self):
        out = os.path.join(self.dir, "never.obj")
        run("deform", "--example", "square", "--method", "magic", "-o", out)
        self.assertFalse(os.path.exists(out))

    def test_help(self):
        p = run("deform", "--help", check_code=0)
        self.assertIn("--handles", p.stdout)
        self.assertIn("--method", p.stdout)


class Eval(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_affine_deformation(self):
        rest = write(os.path.join(self.dir, "rest.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n")
        # x -> diag(2, 0.5) x: ARAP sqrt(1 + 1/4), qc 4, iso 2, fd sqrt(1 + 1/4).
        mapped = write(os.path.join(self.dir, "mapped.obj"), "v 0 0 0\nv 2 0 0\nv 2 0.5 0\nv 0 0.5 0\nf 1 2 3\nf 1 3 4\n")
        for measure, value in [("arap", math.sqrt(1.25)), ("qc", 4.0), ("iso", 2.0), ("fd", math.sqrt(1.25)),
                               ("asap", 1.5 / math.sqrt(2))]:
            with self.subTest(measure=measure):
                s = json.loads(run("eval", rest, mapped, "--measure", measure, "--summary", "-", "-q", check_code=0).stdout)
                self.assertAlmostEqual(s["max_distortion"], value, places=12)
                self.assertEqual(s["flipped"], 0)

    def test_uv_mapped_obj_counts_as_a_parametrization(self):
        # A 3D square tilted by 60 degrees about x, UV = its unrolled layout scaled by 1.5.
        c, sn = math.cos(math.pi / 3), math.sin(math.pi / 3)
        text = (f"v 0 0 0\nv 1 0 0\nv 1 {c} {sn}\nv 0 {c} {sn}\n"
                "vt 0 0\nvt 1.5 0\nvt 1.5 1.5\nvt 0 1.5\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
        obj = write(os.path.join(self.dir, "uv.obj"), text)
        s = json.loads(run("eval", obj, "--summary", "-", "-q", check_code=0).stdout)
        self.assertEqual(s["measure"], "arap")
        self.assertEqual(s["map_kind"], "parametrization")
        self.assertAlmostEqual(s["max_distortion"], math.sqrt(0.5), places=12)
        self.assertEqual(s["output"], "", "no -o")
        written = os.path.join(self.dir, "measured.ply")
        s = json.loads(run("eval", obj, "-o", written, "--summary", "-", "-q", check_code=0).stdout)
        self.assertEqual(s["output"], written, "the -o mesh (eval's summary had no output key)")
        s = json.loads(run("eval", obj, "--measure", "asap", "--summary", "-", "-q", check_code=0).stdout)
        self.assertAlmostEqual(s["max_distortion"], 0.0, places=12)
        self.assertTrue(s["usable"])
        self.assertIn("no solve", s["stop_reason"])
        # fd of a parametrization would be against each triangle's arbitrary in-plane frame.
        p = run("eval", obj, "--measure", "fd", check_code=1)
        self.assertIn("fd of a parametrization needs its target frames", p.stderr)
        # The faces of a UV-mapped OBJ must be the rest's (shuffled ones paired each triangle
        # with another's texture coordinates: 0.73 for an exact map).
        rest = write(os.path.join(self.dir, "rest.obj"), f"v 0 0 0\nv 1 0 0\nv 1 {c} {sn}\nv 0 {c} {sn}\nf 1 2 3\nf 1 3 4\n")
        shuffled = write(os.path.join(self.dir, "shuffled.obj"), text.replace("f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
                                                                               "f 1/1 3/3 4/4\nf 1/1 2/2 3/3\n"))
        p = run("eval", rest, shuffled, check_code=1)
        self.assertIn("different vertices", p.stderr)
        # Some faces with vt, some without: the error says so.
        partial = write(os.path.join(self.dir, "partial.obj"), text.replace("f 1/1 3/3 4/4", "f 1 3 4"))
        p = run("eval", partial, check_code=1)
        self.assertIn("texture coordinates ignored", p.stderr)

    def test_report_of_a_deformation_and_of_a_parametrization(self):
        rest = write(os.path.join(self.dir, "rest.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n")
        mapped = write(os.path.join(self.dir, "mapped.obj"), "v 0 0 0\nv 2 0 0\nv 2 0.5 0\nv 0 0.5 0\nf 1 2 3\nf 1 3 4\n")
        rep = os.path.join(self.dir, "rep")
        p = run("eval", rest, mapped, "--measure", "qc", "--report", rep, check_code=0)
        self.assertIn("report: file://", p.stderr)
        with open(os.path.join(rep, "summary.json")) as f:
            self.assertAlmostEqual(json.load(f)["max_distortion"], 4.0, places=12)
        for name in ("input.svg", "view.svg", "histogram.svg"):
            self.assertTrue(os.path.exists(os.path.join(rep, name)), name)
        with open(os.path.join(rep, "index.html")) as f:
            html = f.read()
        self.assertIn("given map", html)
        self.assertIn("mapped.obj", html)
        self.assertNotIn("certified lower bound", html)  # a given map has no solver bound
        self.assertIn("evaluated (no solve)", html)  # nor a solve to be "solved"
        # A UV map: the surface view, its UV layout and checkerboard.
        c, sn = math.cos(math.pi / 3), math.sin(math.pi / 3)
        obj = write(os.path.join(self.dir, "uv.obj"), f"v 0 0 0\nv 1 0 0\nv 1 {c} {sn}\nv 0 {c} {sn}\n"
                    "vt 0 0\nvt 1.5 0\nvt 1.5 1.5\nvt 0 1.5\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
        rep = os.path.join(self.dir, "uvrep")
        run("eval", obj, "--report", rep, "-q", check_code=0)
        pictures = sorted(os.listdir(rep))
        self.assertIn("view.png", pictures)
        self.assertTrue(any("uv" in n for n in pictures), pictures)
        self.assertTrue(any("checker" in n for n in pictures), pictures)

    def test_flipped_elements_are_counted(self):
        rest = write(os.path.join(self.dir, "rest.obj"), "v 0 0\nv 1 0\nv 0 1\nv 1 1\nf 1 2 3\nf 2 4 3\n")
        mapped = write(os.path.join(self.dir, "flip.obj"), "v 0 0\nv 1 0\nv 0 1\nv -1 -1\nf 1 2 3\nf 2 4 3\n")
        s = json.loads(run("eval", rest, mapped, "--summary", "-", "-q", check_code=0).stdout)
        self.assertEqual(s["flipped"], 1)
        s = json.loads(run("eval", rest, mapped, "--measure", "qc", "--summary", "-", "-q", check_code=0).stdout)
        self.assertIsNone(s["max_distortion"], "an infinite distortion is null in JSON")


class BlasKernels(unittest.TestCase):
    """Debian 12's OpenBLAS falls back to its generic Prescott kernels on processors it does not
    know; the command then runs itself again with OPENBLAS_CORETYPE set (src/runtime/blas_kernels.h)."""

    def kernels(self, **env):
        environment = {k: v for k, v in os.environ.items() if k != "OPENBLAS_CORETYPE"}
        environment.update(env)
        p = subprocess.run([CLI, "deform", "--example", "square", "--method", "l2", "--summary", "-", "--quiet"],
                           capture_output=True, text=True, timeout=60, env=environment)
        self.assertEqual(p.returncode, 0, p.stderr)
        return json.loads(p.stdout).get("blas_kernels")

    def test_the_users_choice_stands_and_no_fallback_on_a_processor_with_avx2(self):
        if self.kernels() is None:
            self.skipTest("the BLAS is not OpenBLAS")
        self.assertEqual(self.kernels(OPENBLAS_CORETYPE="Prescott"), "OpenBLAS Prescott")
        self.assertEqual(self.kernels(OPENBLAS_CORETYPE="Haswell"), "OpenBLAS Haswell")
        with open("/proc/cpuinfo") as f:
            flags = set(next((line for line in f if line.startswith("flags")), "").split())
        if {"avx2", "fma"} <= flags:
            self.assertNotEqual(self.kernels(), "OpenBLAS Prescott", "the generic kernels on a processor with AVX2")


if __name__ == "__main__":
    result = unittest.main(exit=False, verbosity=2).result
    sys.exit(0 if result.wasSuccessful() else 1)
