"""End-to-end tests of `strictmin interp`: one output per t named PREFIX_<t>.<ext>, the
summary, t = 0 / 1 give the poses, and the errors for a mismatched pair. Run by ctest with
STRICTMIN_CLI pointing at the built tool."""
import json
import math
import os
import tempfile
import unittest

from cli_support import DATA, run


def bar_obj(path, turn, nx=20, ny=2):
    """A 10 x 1 grid bar, rolled onto an arc turning by `turn` radians (0: straight)."""
    lines = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = 10.0 * i / nx, 1.0 * j / ny
            if turn:
                r0 = 10.0 / turn
                r = r0 - (y - 0.5)
                x, y = r * math.sin(x / 10.0 * turn), r0 - r * math.cos(x / 10.0 * turn)
            lines.append(f"v {x!r} {y!r} 0")
    for j in range(ny):
        for i in range(nx):
            a, b = j * (nx + 1) + i + 1, j * (nx + 1) + i + 2
            c, d = a + nx + 1, b + nx + 1
            lines += [f"f {a} {b} {d}", f"f {a} {d} {c}"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def read_obj_vertices(path):
    with open(path) as f:
        return [tuple(map(float, l.split()[1:4])) for l in f if l.startswith("v ")]


class Interp(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.src = bar_obj(os.path.join(self.dir, "src.obj"), 0)
        self.dst = bar_obj(os.path.join(self.dir, "dst.obj"), 1.5 * math.pi)

    def tearDown(self):
        self.tmp.cleanup()

    def test_frames_and_summary(self):
        prefix = os.path.join(self.dir, "frame")
        p = run("interp", self.src, self.dst, "--t", "0,0.5,1", "--method", "linf", "-o", prefix,
                "--summary", "-", "--quiet", check_code=0)
        self.assertEqual(p.stderr, "")
        s = json.loads(p.stdout)
        self.assertEqual(s["task"], "interp")
        self.assertEqual(s["kind"], "planar")
        self.assertEqual((s["rotation_blend"], s["rotation_disagreements"], s["warnings"]), ("angles", 0, []))
        self.assertEqual(s["pin"], "centroid")
        self.assertEqual([f["t"] for f in s["frames"]], [0, 0.5, 1])
        for f, name in zip(s["frames"], ["frame_0.obj", "frame_0.5.obj", "frame_1.obj"]):
            self.assertEqual(os.path.basename(f["output"]), name)
            self.assertTrue(os.path.exists(f["output"]))
            self.assertEqual(f["flipped"], 0)
        for out, pose in (("frame_0.obj", self.src), ("frame_1.obj", self.dst)):
            got, want = read_obj_vertices(os.path.join(self.dir, out)), read_obj_vertices(pose)
            self.assertEqual(len(got), len(want))
            self.assertLess(max(abs(a - b) for g, w in zip(got, want) for a, b in zip(g, w)), 1e-5)

    def test_report(self):
        rep = os.path.join(self.dir, "rep")
        p = run("interp", self.src, self.dst, "--t", "0.25,0.5,0.75", "--method", "linf", "--report", rep,
                "--summary", os.path.join(self.dir, "s.json"), check_code=0)
        self.assertIn("report: file://", p.stderr)
        with open(os.path.join(rep, "summary.json")) as f:
            s = json.load(f)
        self.assertEqual([f["t"] for f in s["frames"]], [0.25, 0.5, 0.75])
        with open(os.path.join(self.dir, "s.json")) as f:
            self.assertEqual(json.load(f)["frames"][1]["max_distortion"], s["frames"][1]["max_distortion"])
        for name in ("input.svg", "histogram.svg", "t0.25.svg", "t0.5.svg", "t0.75.svg"):
            path = os.path.join(rep, name)
            self.assertTrue(os.path.exists(path), name)
            with open(path) as f:
                self.assertIn("<svg", f.read(200))
        with open(os.path.join(rep, "index.html")) as f:
            html = f.read()
        for label in ("t = 0.25", "t = 0.5", "t = 0.75", "src.obj", "dst.obj"):
            self.assertIn(label, html)
        # Frames are a sequence, not rival maps: no strict-order verdicts between them.
        self.assertNotIn("Strict order", html)
        # The colour scale is automatic for frames (not the fixed 0.6 of deform and param).
        self.assertNotIn("red = 0.6 ", html)
        self.assertRegex(html, r"red = 0\.00\d+ and above")
        # The middle frame is the most distorted, and its maximum is printed on its card.
        mid = s["frames"][1]["max_distortion"]
        self.assertGreater(mid, 0)
        self.assertGreaterEqual(mid, s["frames"][0]["max_distortion"] - 1e-9)

    def test_mismatched_connectivity(self):
        other = bar_obj(os.path.join(self.dir, "other.obj"), 0, nx=21)
        p = run("interp", self.src, other, "--t", "0.5", check_code=1)
        self.assertIn("vertices", p.stderr)
        self.assertIn("other.obj", p.stderr)

    def test_bad_options(self):
        self.assertIn("outside [0, 1]", run("interp", self.src, self.dst, "--t", "1.5", check_code=1).stderr)
        # Times just outside [0, 1] are shown as given (they read "1 is outside [0, 1]").
        self.assertIn("--t: 1.0000001 is outside [0, 1]",
                      run("interp", self.src, self.dst, "--t", "1.0000001", check_code=1).stderr)
        self.assertIn("--t: -1e-09 is outside [0, 1]", run("interp", self.src, self.dst, "--t=-1e-9", check_code=1).stderr)
        # A time that %g rounds to 1 was written under t = 1's name (the target's frame).
        prefix = os.path.join(self.dir, "near")
        run("interp", self.src, self.dst, "--t", "0.99999999,1", "-o", prefix, "--quiet")
        self.assertTrue(os.path.exists(prefix + "_0.99999999.obj"))
        self.assertTrue(os.path.exists(prefix + "_1.obj"))
        # --lg-extrapolation is refused by interp: its help says so rather than show a default.
        help_line = [l for l in run("interp", "--help").stdout.splitlines() if "--lg-extrapolation" in l]
        self.assertEqual(len(help_line), 1)
        self.assertNotIn("0.5", help_line[0])
        # An empty time (it ran t = 0) and a time given twice (it wrote one file twice).
        self.assertIn("an empty time", run("interp", self.src, self.dst, "--t", "", check_code=1).stderr)
        # --rotation-blend: planar rotations are angles (no jumps); other words are refused.
        self.assertIn("is for 3D poses", run("interp", self.src, self.dst, "--rotation-blend", "tree",
                                             check_code=1).stderr)
        self.assertIn("--rotation-blend takes auto, logarithms or tree, not 'short'",
                      run("interp", self.src, self.dst, "--rotation-blend", "short", check_code=1).stderr)
        self.assertIn("0.5 is given twice", run("interp", self.src, self.dst, "--t", "0.5,0.5", check_code=1).stderr)
        # An empty item of a list (the option parser dropped it: "0.5,,1" ran two frames).
        for times in ("0.5,,1", "0.5,", ",0.5", "0.5, ,1"):
            p = run("interp", self.src, self.dst, "--t", times, "--summary", os.path.join(self.dir, "t.json"),
                    check_code=1)
            self.assertIn(f"--t '{times}': an empty time", p.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "t.json")))
        self.assertIn("--t: 'half' is not a number", run("interp", self.src, self.dst, "--t", "0,half",
                                                           check_code=1).stderr)
        # Lists in several --t values, spaces around the times.
        s = json.loads(run("interp", self.src, self.dst, "--t", "0, 0.25", "--t", "1", "--summary", "-",
                           "--quiet").stdout)
        self.assertEqual([f["t"] for f in s["frames"]], [0, 0.25, 1])
        # -0 is 0 (it wrote PREFIX_0 and PREFIX_-0, one frame twice).
        self.assertIn("0 is given twice", run("interp", self.src, self.dst, "--t", "0,-0", check_code=1).stderr)
        self.assertIn("--pin", run("interp", self.src, self.dst, "--pin", "middle", check_code=1).stderr)
        self.assertIn("single --t", run("interp", self.src, self.dst, "--t", "0.2,0.4", "--distortion",
                                        os.path.join(self.dir, "d.txt"), check_code=1).stderr)

    def test_direct_runs_its_levels_below_the_papers_k_min(self):
        # This bar's distortion at t = 0.5 is about 1.3e-3: with the parametrizations' k_min 0.1
        # direct stopped after its first level (linf's map, "solved"). interp's default is 0.
        def levels(*extra):
            s = json.loads(run("interp", self.src, self.dst, "--t", "0.5", "--method", "direct", "--delta-k", "1e-5",
                               "--summary", "-", "--quiet", *extra).stdout)
            return s["frames"][0]["message"]
        self.assertIn("every element fixed after", levels())
        self.assertNotIn("after 1 levels", levels())
        self.assertIn("the level fell to k_min after 1 levels", levels("--k-min", "0.1"))
        # worst_level_gap is null with or without local steps: direct's levels bound field
        # deviation against the interpolated rotations held fixed, not the distance reported.
        for extra in ([], ["--lg-iterations", "0"]):
            s = json.loads(run("interp", self.src, self.dst, "--t", "0.5", "--method", "direct", "--delta-k", "1e-4",
                               "--summary", "-", "--quiet", *extra).stdout)["frames"][0]
            self.assertIsNone(s["worst_level_gap"], extra)
            self.assertIsNone(s["lower_bound"], extra)
            self.assertIsNotNone(s["fd_step_lower_bound"], extra)
        # The local-global step options of docs/interp.md are accepted (they were refused);
        # --lg-extrapolation is refused by name (it was accepted and ignored: the targets are the
        # blended shapes' rotations, which are not extrapolated).
        run("interp", self.src, self.dst, "--t", "0.5", "--lg-acceleration", "0", "--lg-cold-start", "--quiet")
        p = run("interp", self.src, self.dst, "--t", "0.5", "--lg-extrapolation", "0", "--quiet", check_code=1)
        self.assertIn("--lg-extrapolation does not apply to interp", p.stderr)

    def test_a_discarded_l2_start_is_said(self):
        # linf's local-global starts from the l2 local-global map only when it has no more
        # flipped elements than the given start; when it had more, the summary said nothing
        # and linf ended above l2 without a word. An 8 x 8 grid bent, its centre pushed over.
        n = 8
        rest = [(i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
        faces = [f for j in range(n) for i in range(n)
                 for a in [i + (n + 1) * j] for f in ((a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1))]
        bent = [(x + 0.3 * math.sin(3 * y), 1.2 * y + 0.1 * x * x) for x, y in rest]
        centre = (n + 1) * (n // 2) + n // 2
        bent[centre] = (bent[centre][0] + 0.3, bent[centre][1] + 0.3)

        def obj(name, points):
            text = "".join(f"v {x} {y} 0\n" for x, y in points) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
            path = os.path.join(self.dir, name)
            with open(path, "w") as f:
                f.write(text)
            return path
        src, dst = obj("g.obj", rest), obj("g_pushed.obj", bent)
        s = json.loads(run("interp", src, dst, "--t", "0.5", "--method", "linf", "--summary", "-", "--quiet").stdout)
        self.assertIn("was not taken as the start: it has more flipped elements (", s["frames"][0]["message"])

    def test_report_command_points_to_interps_own_report(self):
        summary = os.path.join(self.dir, "ip.json")
        run("interp", self.src, self.dst, "--t", "0.5", "--method", "l2", "-o", os.path.join(self.dir, "ip"), "--summary",
            summary, "--quiet", check_code=0)
        p = run("report", os.path.join(self.dir, "R"), summary, check_code=1)
        self.assertIn("interp ... --report DIR", p.stderr)

    def test_report_of_a_surface_says_flips_are_not_defined(self):
        # On a surface in 3D the summary's flipped is null (no orientation): the report said
        # "flipped elements 0 of N".
        def bumpy(path, lift):
            lines = [f"v {i} {j} {lift * math.sin(i) * math.cos(j)}" for j in range(4) for i in range(4)]
            lines += [f"f {1 + i + 4 * j} {2 + i + 4 * j} {6 + i + 4 * j}\nf {1 + i + 4 * j} {6 + i + 4 * j} {5 + i + 4 * j}"
                      for j in range(3) for i in range(3)]
            with open(path, "w") as f:
                f.write("\n".join(lines) + "\n")
            return path
        src, dst = bumpy(os.path.join(self.dir, "s.obj"), 0.3), bumpy(os.path.join(self.dir, "d.obj"), 0.8)
        summary = os.path.join(self.dir, "bumpy.json")
        rep = os.path.join(self.dir, "bumpy")
        run("interp", src, dst, "--t", "0.5", "--summary", summary, "--report", rep, "--quiet", check_code=0)
        with open(summary) as f:
            s = json.load(f)
        self.assertEqual(s["kind"], "surface")
        self.assertIsNone(s["frames"][0]["flipped"])
        with open(os.path.join(rep, "index.html")) as f:
            html = f.read()
        self.assertIn("not defined (surface)", html)
        # The report's time is the summary's solver_time_s (the solve alone; it was in no key).
        frame = s["frames"][0]
        self.assertLessEqual(frame["solver_time_s"], frame["time_s"])
        # eval of the same two surfaces says the same (it wrote "flipped": 0, "0 of 18" in its report).
        p = run("eval", src, dst, "--measure", "arap", "--summary", "-", "--report", rep + "_eval", check_code=0)
        self.assertIsNone(json.loads(p.stdout)["flipped"])
        self.assertIn("flips not defined (surface)", p.stderr)
        with open(os.path.join(rep + "_eval", "index.html")) as f:
            self.assertIn("not defined (surface)", f.read())
        self.assertNotIn("flipped elements</td><td class=\"v\">0 of", html)

    def test_exact_frames_of_a_surface_are_solved(self):
        # t = 0 and t = 1 reproduce the poses: local-global stops at once. On lion's surface the
        # rest frames leave about 1e-11 (6e-12 here), which the zero test at 1e-12 missed: both
        # frames ran to the 100-step cap chasing round-off (max-iterations, exit 2).
        src = os.path.join(DATA, "interp", "lion_reference.obj")
        dst = os.path.join(DATA, "interp", "lion_05.obj")
        if not (os.path.exists(src) and os.path.exists(dst)):
            self.skipTest("no shared data")
        summary = os.path.join(self.dir, "lion.json")
        run("interp", src, dst, "--t", "0,1", "--method", "l2", "-o", os.path.join(self.dir, "lion"), "--summary",
            summary, "--quiet", check_code=0)
        with open(summary) as f:
            frames = json.load(f)["frames"]
        for frame in frames:
            self.assertEqual(frame["status"], "solved")
            self.assertLess(frame["max_distortion"], 1e-10)
            self.assertIn("zero to rounding", frame["stop_reason"])

    def test_shared_tet_bar(self):
        rest = os.path.join(DATA, "interp", "tetbar_rest.mesh")
        if not os.path.exists(rest):
            self.skipTest("no shared data")
        prefix = os.path.join(self.dir, "tetbar")
        rep = os.path.join(self.dir, "rep")
        s = json.loads(run("interp", rest, os.path.join(DATA, "interp", "tetbar_init.mesh"), "--t", "0.5",
                           "-o", prefix, "--summary", "-", "--quiet", "--report", rep).stdout)
        self.assertEqual(s["kind"], "tets")
        # L2 local-global used to be still moving at its default cap of 100 here; with
        # Anderson acceleration it converges within the cap (exit 0).
        frame = s["frames"][0]
        self.assertEqual(frame["status"], "solved")
        self.assertTrue(frame["usable"])
        self.assertIn("converged", frame["stop_reason"])
        self.assertTrue(os.path.exists(prefix + "_0.5.mesh"))
        with open(os.path.join(rep, "t0.5.png"), "rb") as f:  # tet boundaries are drawn as PNG
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")


if __name__ == "__main__":
    unittest.main()
