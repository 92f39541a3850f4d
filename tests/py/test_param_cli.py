"""End-to-end tests of `strictmin param`: the UV OBJ, the summary keys, the errors for
meshes that are not disks (exit 1). Run by ctest with STRICTMIN_CLI set."""
import json
import math
import os
import sys
import tempfile
import unittest

from cli_support import CLI, run


def cap_obj(rings=5, sectors=16, max_polar=1.1, drop_fan=False):
    """A spherical cap as OBJ text (drop_fan: without the polar fan, an annulus)."""
    lines = ["v 0 0 1"]
    for r in range(1, rings + 1):
        for s in range(sectors):
            t, a = max_polar * r / rings, 2 * math.pi * s / sectors
            lines.append(f"v {math.sin(t) * math.cos(a)} {math.sin(t) * math.sin(a)} {math.cos(t)}")

    def vid(r, s):
        return 2 + (r - 1) * sectors + s % sectors  # 1-based

    if not drop_fan:
        lines += [f"f 1 {vid(1, s)} {vid(1, s + 1)}" for s in range(sectors)]
    for r in range(1, rings):
        for s in range(sectors):
            lines.append(f"f {vid(r, s)} {vid(r + 1, s)} {vid(r + 1, s + 1)}")
            lines.append(f"f {vid(r, s)} {vid(r + 1, s + 1)} {vid(r, s + 1)}")
    return "\n".join(lines) + "\n"


TETRA = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
KEYS = {"task", "input", "output", "method", "measure", "init", "elements", "vertices", "max_distortion",
        "l2_distortion", "flips", "boundary_overlap", "status", "time_s"}


class Param(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.cap = os.path.join(self.dir, "cap.obj")
        with open(self.cap, "w") as f:
            f.write(cap_obj())

    def tearDown(self):
        self.tmp.cleanup()

    def path(self, name, text):
        p = os.path.join(self.dir, name)
        with open(p, "w") as f:
            f.write(text)
        return p

    def test_linf_writes_uv_obj_and_summary(self):
        out = os.path.join(self.dir, "uv.obj")
        p = run("param", self.cap, "-o", out, "--method", "linf", "--summary", "-", "--quiet", check_code=0)
        s = json.loads(p.stdout)
        self.assertTrue(KEYS <= s.keys(), KEYS - s.keys())
        self.assertEqual((s["task"], s["method"], s["measure"], s["init"]), ("param", "linf", "arap", "tutte"))
        self.assertEqual(s["flips"], 0)
        self.assertFalse(s["boundary_overlap"])
        self.assertEqual(s["warnings"], [])
        self.assertIn("lower_bound", s)
        with open(out) as f:
            text = f.read().splitlines()
        vt = [l for l in text if l.startswith("vt ")]
        faces = [l for l in text if l.startswith("f ")]
        self.assertEqual(len(vt), 1 + 5 * 16)
        self.assertEqual(len(faces), s["elements"])
        self.assertTrue(all("/" in f for f in faces), faces[:2])
        # eval measures the written map the same way.
        e = run("eval", self.cap, out, "--measure", "arap", "--summary", "-", "--quiet", check_code=0)
        self.assertAlmostEqual(json.loads(e.stdout)["max_distortion"], s["max_distortion"], places=5)

    def test_a_folded_map_is_warned_about(self):
        # A cap reaching almost round the sphere (polar angle 3.0): its flattenings fold (l2 96
        # and linf 144 of 360 triangles flipped), each "solved" by its method's criterion. The
        # warning says what the status does not; --no-flips gives a map without.
        cap = self.path("deep.obj", cap_obj(8, 24, 3.0))
        p = run("param", cap, "--method", "l2", "--summary", "-", check_code=0)
        s = json.loads(p.stdout)
        self.assertGreater(s["flips"], 0)
        self.assertEqual(len(s["warnings"]), 1)
        self.assertIn(f"{s['flips']} of 360 triangles are flipped", s["warnings"][0])
        self.assertIn("--no-flips keeps every triangle's orientation", s["warnings"][0])
        self.assertIn("param: warning: " + s["warnings"][0], p.stderr)
        s = json.loads(run("param", cap, "--method", "linf", "--no-flips", "--summary", "-", "--quiet",
                           check_code=0).stdout)
        self.assertEqual((s["flips"], s["warnings"]), (0, []))

    def test_init_methods_and_lscm_start(self):
        for method in ("tutte", "lscm"):
            s = json.loads(run("param", self.cap, "--method", method, "--summary", "-", "--quiet", check_code=0).stdout)
            self.assertEqual(s["method"], method)
        s = json.loads(run("param", self.cap, "--init", "lscm", "--method", "l2", "--summary", "-", "--quiet",
                           check_code=0).stdout)
        self.assertEqual(s["init"], "lscm")
        self.assertIn("local_global_iterations", s)
        # relax: init stays the starting map, relax's own start is relax_init (it overwrote init).
        s = json.loads(run("param", self.cap, "--init", "lscm", "--method", "relax", "--sweeps", "2", "--summary", "-",
                           "--quiet", check_code=0).stdout)
        self.assertEqual((s["init"], s["relax_init"]), ("lscm", "linf"))
        s = json.loads(run("param", self.cap, "--method", "tutte", "--summary", "-", "--quiet", check_code=0).stdout)
        self.assertIn("Tutte", s["stop_reason"])
        # --no-flips with the starting map itself: no solve to constrain (LSCM's map kept its
        # flips and the summary said no_flips: true).
        for method in ("tutte", "lscm"):
            p = run("param", self.cap, "--method", method, "--no-flips", check_code=1)
            self.assertIn(f"--no-flips applies to a solve, and --method {method} returns the starting map", p.stderr)

    def test_closed_mesh_is_rejected(self):
        p = run("param", self.path("tet.obj", TETRA), "-o", os.path.join(self.dir, "x.obj"), check_code=1)
        self.assertIn("closed", p.stderr)
        self.assertIn("genus 0", p.stderr)
        self.assertIn("cut it to a disk first", p.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "x.obj")))

    def test_two_boundary_loops_are_rejected(self):
        p = run("param", self.path("annulus.obj", cap_obj(drop_fan=True)), check_code=1)
        self.assertIn("2 boundary loops", p.stderr)

    def test_unknown_measure_and_method(self):
        self.assertIn("unknown measure", run("param", self.cap, "--measure", "bogus", check_code=1).stderr)
        self.assertIn("unknown method", run("param", self.cap, "--method", "bogus", check_code=1).stderr)
        # param's own names are in the lists; --help shows param's default start.
        self.assertIn("use tutte, lscm", run("param", self.cap, "--method", "bogus", check_code=1).stderr)
        self.assertIn("use tutte, lscm, l2, lp, irls or linf", run("param", self.cap, "--init", "x", check_code=1).stderr)
        self.assertIn("--init TEXT=tutte", run("param", "--help", check_code=0).stdout)

    def test_init_contradicting_the_start_method_is_refused(self):
        """--method tutte is Tutte's map itself: --init lscm beside it was silently dropped."""
        out = os.path.join(self.dir, "never.obj")
        for method, init in (("tutte", "lscm"), ("lscm", "tutte")):
            err = run("param", self.cap, "--method", method, "--init", init, "-o", out, check_code=1).stderr
            self.assertIn(f"--init {init} contradicts --method {method}", err)
            self.assertFalse(os.path.exists(out))
        for method in ("tutte", "lscm"):  # the same map twice is no contradiction
            run("param", self.cap, "--method", method, "--init", method, "--quiet", check_code=0)

    def test_report(self):
        rep = os.path.join(self.dir, "rep")
        run("param", self.cap, "--method", "l2", "--report", rep, "--quiet", check_code=0)
        self.assertTrue(os.path.exists(os.path.join(rep, "index.html")))
        self.assertTrue(os.path.exists(os.path.join(rep, "summary.json")))

    def test_fd_report_names_the_starting_maps_rotations(self):
        """param's fd is ||J - R|| against the starting map's rotations: its report said ||J - I||."""
        rep = os.path.join(self.dir, "rep_fd")
        run("param", self.cap, "--measure", "fd", "--method", "l2", "--report", rep, "--quiet", check_code=0)
        with open(os.path.join(rep, "index.html"), encoding="utf-8") as f:
            html = f.read().replace("&#39;", "'")
        self.assertNotIn("\u2016J \u2212 I\u2016", html)
        self.assertIn("\u2016J \u2212 R\u2016 from the starting map's rotations", html)


if __name__ == "__main__":
    if not os.path.exists(CLI) and "/" in CLI:
        sys.exit(77)
    unittest.main()
