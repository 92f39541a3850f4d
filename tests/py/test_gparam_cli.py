"""End-to-end tests of `strictmin gparam` (docs/gparam.md): the summary contract, the
per-corner UV OBJ, field files, the report, and bad input (exit 1, a message naming the
problem, no output file). Run by ctest with STRICTMIN_CLI set."""
import json
import math
import os
import sys
import tempfile
import unittest

from cli_support import CLI, DATA, run


def cube_obj(n=3, side=2.0, offset=0.0):
    """The surface of a cube as OBJ text, each side an n by n grid (outward triangles)."""
    index, verts, faces = {}, [], []

    def vid(p):
        if p not in index:
            index[p] = len(verts) + 1
            verts.append(p)
        return index[p]

    for axis in range(3):
        for sign in (0, 1):
            a, b = (axis + 1) % 3, (axis + 2) % 3
            if sign == 0:
                a, b = b, a
            for i in range(n):
                for j in range(n):
                    def pt(ii, jj):
                        p = [0, 0, 0]
                        p[axis] = sign * n
                        p[a], p[b] = ii, jj
                        return tuple(p)
                    p00, p10, p11, p01 = vid(pt(i, j)), vid(pt(i + 1, j)), vid(pt(i + 1, j + 1)), vid(pt(i, j + 1))
                    faces += [(p00, p10, p11), (p00, p11, p01)]
    lines = [f"v {x * side / n + offset} {y * side / n} {z * side / n}" for x, y, z in verts]
    lines += [f"f {a} {b} {c}" for a, b, c in faces]
    return lines, len(verts)


def edge_aligned_field(lines):
    """The cube's field along its edges as field-file text (x, or y on the faces normal to x):
    the smoothest field may come out at any global angle, and then the corners are not a whole
    number of grid units apart."""
    verts = [[float(x) for x in l.split()[1:]] for l in lines if l.startswith("v ")]
    field = []
    for l in lines:
        if l.startswith("f "):
            corners = [verts[int(i) - 1] for i in l.split()[1:]]
            normal_x = all(abs(c[0] - corners[0][0]) < 1e-12 for c in corners)
            field.append("0 1 0" if normal_x else "1 0 0")
    return "\n".join(field) + "\n"


class CubeCase(unittest.TestCase):
    """A temporary folder holding the cube (cube.obj), with helpers to write and name files there."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        lines, _ = cube_obj()
        self.cube = self.write("cube.obj", "\n".join(lines) + "\n")

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, name, text):
        p = os.path.join(self.dir, name)
        with open(p, "w") as f:
            f.write(text)
        return p

    def out(self, name):
        return os.path.join(self.dir, name)


KEYS = {"task", "singularities", "singularity_indices", "euler_characteristic", "seam_edges", "edge_length",
        "seam_error", "max_distortion", "l2_distortion", "flipped", "status", "method", "measure"}


class GParam(CubeCase):
    def gparam(self, *args, code=0):
        summary = self.out("s.json")
        run("gparam", *args, "--summary", summary, "--quiet", check_code=code)
        with open(summary) as f:
            return json.load(f)

    def test_cube_summary_and_uv(self):
        out = self.out("uv.obj")
        for method in ("l2", "linf", "relax"):
            s = self.gparam(self.cube, "-o", out, "--method", method, "--edge-length", "0.5")
            self.assertTrue(KEYS <= set(s), KEYS - set(s))
            self.assertEqual(s["task"], "gparam")
            self.assertEqual(s["euler_characteristic"], 2)
            self.assertEqual(s["singularities"], 8)
            self.assertEqual(sorted(x["index"] for x in s["singularity_indices"]), [1] * 8)
            self.assertEqual(s["edge_length"], 0.5)
            self.assertLess(s["seam_error"], 1e-9)
            # The axis-aligned field of a cube is exact up to a global angle: no distortion.
            self.assertLess(s["max_distortion"], 1e-6, method)
            self.assertEqual(s["status"], "solved")
            if method == "linf":
                self.assertIn("lower_bound", s)
            if method == "relax":
                self.assertIn("sweeps", s)
        with open(out) as f:
            text = f.read().split("\n")
        vts = [l for l in text if l.startswith("vt ")]
        fs = [l for l in text if l.startswith("f ")]
        self.assertEqual(len(vts), s["cut_mesh_vertices"])
        self.assertEqual(len(fs), s["elements"])
        self.assertTrue(all("/" in l for l in fs))

    def test_eval_measures_the_obj_at_the_edge_length(self):
        # gparam's OBJ holds the map divided by the edge length h: eval measured that layout
        # (ARAP 4.24 on the cube with h = 0.25, where gparam says 0) without a word. It now
        # warns about a seamed layout, and --uv-scale h measures the map gparam measured.
        run("gparam", self.cube, "--measure", "arap", "--method", "linf", "--edge-length", "0.25", "-o",
            self.out("a.obj"), "--summary", self.out("a.json"), "-q", check_code=0)
        with open(self.out("a.json")) as f:
            g = json.load(f)
        p = run("eval", self.cube, self.out("a.obj"), "--summary", "-", check_code=0)
        self.assertIn("give --uv-scale EDGE_LENGTH", p.stderr)
        self.assertAlmostEqual(json.loads(p.stdout)["max_distortion"], math.sqrt(2) * 3, places=9)
        p = run("eval", self.cube, self.out("a.obj"), "--uv-scale", str(g["edge_length"]), "--summary", "-",
                check_code=0)
        self.assertNotIn("--uv-scale EDGE_LENGTH", p.stderr)
        e = json.loads(p.stdout)
        self.assertLess(abs(e["max_distortion"] - g["max_distortion"]), 1e-9)
        self.assertEqual(e["uv_scale"], 0.25)
        # report recomputes that summary's distortion at its uv_scale (it refused it as
        # disagreeing with its own map, 4.24 against 0).
        run("eval", self.cube, self.out("a.obj"), "--uv-scale", "0.25", "--summary", self.out("e.json"), "-q",
            check_code=0)
        run("report", self.out("r"), self.out("e.json"), "-q", check_code=0)
        for bad, why in (("0", "--uv-scale"), ("nan", "not a finite number")):
            self.assertIn(why, run("eval", self.cube, self.out("a.obj"), "--uv-scale", bad, check_code=1).stderr)
        for given in ("2", "1"):  # (1 was taken without a word)
            p = run("eval", self.cube, self.cube, "--uv-scale", given, check_code=1)
            self.assertIn("has no texture coordinates (vt) to scale", p.stderr)
        p = run("eval", self.cube, self.out("a.obj"), "--uv-scale", "1e300", check_code=1)
        self.assertIn("--uv-scale 1e+300: the texture coordinates times it are beyond 1e150", p.stderr)

    def test_surfaces_with_boundary(self):
        """A cube with one grid cell cut out of a side (a square hole: its corners are -1/4 on
        the boundary) and a cube without its top (a box: its bottom corners +1/4 inside, its rim
        straight): the field follows the boundary, Poincare-Hopf holds with the boundary's
        indices, and every method maps them without distortion."""
        lines, _ = cube_obj()
        verts = [l for l in lines if l.startswith("v ")]
        faces = [l for l in lines if l.startswith("f ")]
        height = [float(v.split()[3]) for v in verts]
        top = [f for f in faces if all(height[int(i) - 1] == 2.0 for i in f.split()[1:])]
        cases = {
            "hole.obj": (faces[:8] + faces[10:], 1, {(1, False): 8, (-1, True): 4}),  # the centre cell of a side
            "box.obj": ([f for f in faces if f not in top], 1, {(1, False): 4}),
        }
        for name, (kept, chi, counts) in cases.items():
            used = sorted({int(i) for f in kept for i in f.split()[1:]})
            new = {old: k + 1 for k, old in enumerate(used)}  # without the vertices no face uses
            kept = ["f " + " ".join(str(new[int(i)]) for i in f.split()[1:]) for f in kept]
            mesh = self.write(name, "\n".join([verts[i - 1] for i in used] + kept) + "\n")
            for method in ("l2", "linf", "relax"):
                s = self.gparam(mesh, "-o", self.out("uv.obj"), "--method", method)
                self.assertEqual(s["status"], "solved", (name, method))
                self.assertEqual(s["boundary_loops"], 1)
                self.assertEqual(s["euler_characteristic"], chi)
                found = {}
                for x in s["singularity_indices"]:
                    key = (x["index"], x.get("boundary", False))
                    found[key] = found.get(key, 0) + 1
                self.assertEqual(found, counts, name)
                self.assertEqual(sum(x["index"] for x in s["singularity_indices"]), 4 * chi)
                self.assertLess(s["max_distortion"], 1e-6, (name, method))
                self.assertLess(s["seam_error"], 1e-9)
        # The box with the top's inner vertices still listed: named as unused, not as a boundary.
        unused = self.write("unused.obj", "\n".join(verts + cases["box.obj"][0]) + "\n")
        p = run("gparam", unused, "-o", self.out("bad.obj"), check_code=1)
        self.assertIn("belongs to no face", p.stderr)
        self.assertFalse(os.path.exists(self.out("bad.obj")))
        report = self.out("box_report")
        run("gparam", self.out("box.obj"), "--report", report, "--quiet")
        self.assertTrue(os.path.exists(os.path.join(report, "index.html")))

    def test_integer_grid(self):
        # The cube of side 2 at h = 0.5 with its edge-aligned field: its corners are 4 grid units
        # apart, so the rounded map keeps distortion 0, with every corner and seam translation on
        # the grid.
        lines, _ = cube_obj()
        field_file = self.write("edges.txt", edge_aligned_field(lines))
        out = self.out("grid.obj")
        for method in ("l2", "linf", "relax"):
            s = self.gparam(self.cube, "-o", out, "--method", method, "--edge-length", "0.5", "--integer-grid",
                            "--field", field_file)
            self.assertTrue(s["integer_grid"])
            self.assertLess(s["integer_error"], 1e-9, method)
            self.assertIn(s["rounded_singularities"], (7, 8))  # wedge 0 may be a corner, on the grid already
            self.assertEqual(s["rounded_translations"], s["seam_branches"])
            self.assertLess(s["max_distortion"], 1e-6, method)
            self.assertEqual(s["status"], "solved")
        with open(out) as f:
            uv = [[float(x) for x in l.split()[1:3]] for l in f if l.startswith("vt ")]
        corners = [p for p in uv if abs(p[0] - round(p[0])) < 1e-9 and abs(p[1] - round(p[1])) < 1e-9]
        self.assertGreaterEqual(len(corners), 8)
        report = self.out("grid_report")
        run("gparam", self.cube, "-o", out, "--edge-length", "0.5", "--integer-grid", "--field", field_file,
            "--report", report, "--quiet", check_code=0)
        with open(os.path.join(report, "index.html")) as f:
            self.assertIn("Integer-grid map: singular vertices and seam translations rounded to the grid", f.read())
        # At h = 0.8 the corners, 2.5 grid units apart, cannot all be integer points: distortion.
        s = self.gparam(self.cube, "-o", out, "--method", "linf", "--edge-length", "0.8", "--integer-grid",
                        "--field", field_file)
        self.assertGreater(s["lower_bound"], 1e-2)
        self.assertLess(s["integer_error"], 1e-9)
        self.assertEqual(s["grid_guide"], "l2")
        # The L-infinity guide: the same corners on the grid, the guide in the summary.
        s = self.gparam(self.cube, "-o", out, "--method", "linf", "--edge-length", "0.5", "--integer-grid",
                        "--field", field_file, "--grid-guide", "linf")
        self.assertEqual(s["grid_guide"], "linf")
        self.assertLess(s["integer_error"], 1e-9)
        self.assertLess(s["max_distortion"], 1e-6)
        s = self.gparam(self.cube, "-o", out, "--edge-length", "0.8")
        self.assertFalse(s["integer_grid"])
        self.assertNotIn("integer_error", s)
        self.assertNotIn("grid_guide", s)
        self.expect_bad([self.cube, "--grid-guide", "linf"], ["--grid-guide applies to --integer-grid only"])
        self.expect_bad([self.cube, "--integer-grid", "--grid-guide", "l1"], ["--grid-guide takes l2 or linf, not 'l1'"])

    def test_field_round_trip(self):
        field = self.out("field.txt")
        a = self.gparam(self.cube, "--field-out", field)
        with open(field) as f:
            self.assertEqual(len([l for l in f if l.strip()]), a["elements"])
        b = self.gparam(self.cube, "--field", field)
        self.assertEqual(a["singularity_indices"], b["singularity_indices"])
        self.assertLess(abs(a["max_distortion"] - b["max_distortion"]), 1e-6)

    def test_side_by_side_report(self):
        """The paper's Figures 8-9: histograms of several methods side by side (strictmin report)."""
        summaries = []
        for method in ("l2", "linf", "relax"):
            summary = self.out(f"{method}.json")
            run("gparam", self.cube, "-o", self.out(f"{method}.obj"), "--method", method, "--summary", summary,
                "--distortion", self.out(f"{method}.txt"), "--quiet", check_code=0)
            summaries += ["--run", summary]
        report = self.out("side")
        run("report", report, *summaries, "--quiet", check_code=0)
        self.assertTrue(os.path.exists(os.path.join(report, "index.html")))
        self.assert_field_deviation_from_the_field(os.path.join(report, "index.html"))

    def assert_field_deviation_from_the_field(self, page):
        """gparam's fd is ||J - R|| against the cross field's frames: its reports said ||J - I||."""
        with open(page, encoding="utf-8") as f:
            html = f.read()
        self.assertNotIn("\u2016J \u2212 I\u2016", html)
        self.assertIn("\u2016J \u2212 R\u2016 from the cross field's frames", html.replace("&#39;", "'"))

    def test_report_names_the_fields_frames(self):
        report = self.out("one")
        run("gparam", self.cube, "--method", "l2", "--report", report, "--quiet", check_code=0)
        self.assert_field_deviation_from_the_field(os.path.join(report, "index.html"))

    def test_curvature_field(self):
        s = self.gparam(self.cube, "--field", "curvature")
        self.assertEqual(s["field"], "curvature")
        self.assertEqual(s["singularities"], 8)
        self.assertLess(s["max_distortion"], 1e-6)  # the cube's edges are its principal directions

    def test_unit_field(self):
        """--field unit: the smoothest field lowered among unit fields; the cube's axis-aligned
        field (zero energy) is kept, with its eight corners and no distortion."""
        s = self.gparam(self.cube, "--field", "unit")
        self.assertEqual(s["field"], "unit")
        self.assertEqual(s["singularities"], 8)
        self.assertGreaterEqual(s["field_unit_steps"], 1)
        self.assertLessEqual(s["field_energy"], s["field_eigen_energy"])
        self.assertLess(s["field_energy"], 1e-9)
        self.assertLess(s["max_distortion"], 1e-6)
        p = run("gparam", self.cube, "-o", self.out("u.obj"), "--field", "unit", check_code=0)
        self.assertRegex(p.stderr, r"field: unit, .* unit steps")

    def test_cones_round_trip_and_parallel(self):
        """--cones-out writes the field's singularities in the cone-file format (the cube's eight
        corners: angle 3 pi/2); --cones reads them back into the field with exactly those cones,
        here the axis-aligned field; --parallel keeps a field's singularities."""
        cones = self.out("cones.txt")
        self.gparam(self.cube, "--cones-out", cones)
        with open(cones) as f:
            angles = [float(l) for l in f if l.strip()]
        _, nv = cube_obj()
        self.assertEqual(len(angles), nv)
        self.assertEqual(sum(1 for a in angles if abs(a - 1.5 * math.pi) < 1e-12), 8)
        self.assertEqual(sum(1 for a in angles if abs(a - 2 * math.pi) < 1e-12), nv - 8)
        s = self.gparam(self.cube, "--cones", cones, "--method", "linf")
        self.assertEqual(s["field"], "cones")
        self.assertTrue(s["field_parallel"])
        self.assertEqual(s["cones_missed"], 0)
        self.assertEqual(s["singularities"], 8)
        self.assertLess(s["field_energy"], 1e-9)
        self.assertLess(s["max_distortion"], 1e-6)
        s = self.gparam(self.cube, "--parallel", "--field", "unit")
        self.assertEqual(s["field"], "unit")
        self.assertTrue(s["field_parallel"])
        self.assertEqual(s["cones_missed"], 0)
        self.assertEqual(s["singularities"], 8)
        self.assertIn("field_energy_before_parallel", s)
        p = run("gparam", self.cube, "-o", self.out("p.obj"), "--parallel", check_code=0)
        self.assertRegex(p.stderr, r"field: smoothest, .* made parallel in")

    def test_cow_parallel_field(self):
        """--parallel on cow: the same singularities, a lower energy and a lower L-infinity
        maximum (measured 2026-11-26: energy 3033 -> 2082, maximum 0.464 -> 0.390)."""
        cow = os.path.join(DATA, "closed", "cow.obj")
        if not os.path.exists(cow):
            self.skipTest(f"no {cow}")
        a = self.gparam(cow, "--method", "linf")
        b = self.gparam(cow, "--method", "linf", "--parallel")
        self.assertEqual(b["singularity_indices"], a["singularity_indices"])
        self.assertAlmostEqual(b["field_energy_before_parallel"], a["field_energy"], delta=1e-9 * a["field_energy"])
        self.assertLess(b["field_energy"], 0.8 * a["field_energy"])
        self.assertLess(b["max_distortion"], 0.92 * a["max_distortion"])
        self.assertFalse(a["field_parallel"])

    def test_elephant_cone_file(self):
        """--cones with the shared elephant's cone file (genus 3, cones down to -3/4): the
        summary's cones_missed is the number of vertices whose index in --cones-out differs
        from the file's (measured: 17), and the field's own indices add up to chi."""
        elephant = os.path.join(DATA, "closed", "elephant.obj")
        cones = os.path.join(DATA, "closed", "elephant.cones.txt")
        if not (os.path.exists(elephant) and os.path.exists(cones)):
            self.skipTest(f"no {elephant} or {cones}")
        out = self.out("elephant_cones.txt")
        s = self.gparam(elephant, "--cones", cones, "--cones-out", out)

        def quarters(path):
            with open(path) as f:
                return [round((2 * math.pi - float(l)) / (math.pi / 2)) for l in f if l.strip()]

        asked, got = quarters(cones), quarters(out)
        self.assertEqual(s["cones_missed"], sum(1 for a, b in zip(asked, got) if a != b))
        self.assertGreater(s["cones_missed"], 0)
        self.assertEqual(sum(got), 4 * s["euler_characteristic"])
        self.assertEqual(s["singularities"], sum(1 for q in got if q != 0))
        self.assertLess(s["seam_error"], 1e-9)

    def test_quads_sets_the_edge_length(self):
        s = self.gparam(self.cube, "--quads", "96")
        # area 6 * 2^2 = 24, 96 squares: h = 0.5
        self.assertAlmostEqual(s["edge_length"], 0.5, places=12)

    def expect_bad(self, args, words):
        out = self.out("bad.obj")
        p = run("gparam", *args, "-o", out, check_code=1)
        for w in words:
            self.assertIn(w, p.stderr)
        self.assertFalse(os.path.exists(out), "an output file was written")

    def test_bad_inputs(self):
        lines, nv = cube_obj()
        two = lines + [l for l in cube_obj(offset=5.0)[0] if l.startswith("v ")]
        two += [f"f {' '.join(str(int(i) + nv) for i in l.split()[1:])}" for l in lines if l.startswith("f ")]
        self.expect_bad([self.write("two.obj", "\n".join(two) + "\n")], ["2 connected components"])
        open_box = [l for l in lines if not l.startswith("f ")] + [l for l in lines if l.startswith("f ")][2:]
        self.expect_bad([self.write("open.obj", "\n".join(open_box) + "\n"), "--integer-grid"],
                        ["open.obj", "1 boundary loop", "--integer-grid", "closed surfaces"])
        fins = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n"
        self.expect_bad([self.write("fins.obj", fins)], ["non-manifold"])
        self.expect_bad([self.cube, "--edge-length", "0"], ["--edge-length"])
        # Local-global flags with fd (no local steps) were ignored.
        self.expect_bad([self.cube, "--lg-iterations", "3"], ["--lg-iterations applies to --measure arap (its local-global iterations), not fd"])
        # Out of the surface's scale (sqrt(area) = 2.45 here): the UV would overflow (1e-320 gave
        # inf texture coordinates reported as solved) or lose every digit.
        for h in ("1e-320", "1e-12", "1e12"):
            self.expect_bad([self.cube, "--edge-length", h], ["--edge-length", "out of scale", "square root of its area"])
        # The map is per-corner vt: only .obj holds it (.off and .ply kept the input alone).
        for ext in ("off", "ply"):
            out = self.out("uv." + ext)
            p = run("gparam", self.cube, "-o", out, check_code=1)
            self.assertIn("only .obj", p.stderr)
            self.assertFalse(os.path.exists(out))
        # A vertex used by no face: one message, not a warning that it is ignored and then an error.
        unused = self.write("unused.obj", "v 9 9 9\n" + "\n".join(
            l if not l.startswith("f ") else "f " + " ".join(str(int(i) + 1) for i in l.split()[1:]) for l in lines) + "\n")
        p = run("gparam", unused, "-o", self.out("bad.obj"), check_code=1)
        self.assertIn("vertex 0 (0-based) belongs to no face", p.stderr)
        self.assertNotIn("ignored", p.stderr)
        self.expect_bad([self.cube, "--field", "smoothes"], ["--field smoothes", "not smoothest, unit or curvature"])
        self.expect_bad([self.cube, "--edge-length", "-1"], ["--edge-length"])
        self.expect_bad([self.cube, "--quads", "0"], ["--quads"])
        self.expect_bad([self.cube, "--field", "curvature", "--curvature-alignment", "0"], ["--curvature-alignment"])
        # The alignment belongs to the curvature field: elsewhere it would be ignored in silence.
        self.expect_bad([self.cube, "--curvature-alignment", "0.5"], ["--curvature-alignment", "--field curvature"])
        self.expect_bad([self.cube, "--field", "unit", "--curvature-alignment", "0.5"], ["the field is unit"])
        self.expect_bad([self.cube, "--measure", "qc"], ["--measure"])
        self.expect_bad([self.cube, "--field", self.out("missing.txt")], ["missing.txt"])
        field = self.out("f.txt")
        self.gparam(self.cube, "--field-out", field)
        with open(field) as f:
            rows = [l for l in f if l.strip()]
        self.expect_bad([self.cube, "--field", self.write("short.txt", "".join(rows[:-1]))], ["short.txt", "directions"])
        self.expect_bad([self.cube, "--field", self.write("zero.txt", "".join(rows[:3] + ["0 0 0\n"] + rows[4:]))],
                        ["zero.txt", "line 4", "face 3"])
        self.expect_bad([self.cube, "--field", self.write("nan.txt", "".join(["nan 1 0\n"] + rows[1:]))],
                        ["nan.txt", "line 1", "not finite"])
        # The file's own line, past comments and blank lines (it said line 4 for line 7), and a
        # byte-order mark is no part of the first number.
        header = "# my field\n# generated\n\n"
        self.expect_bad([self.cube, "--field", self.write("hdr.txt", header + "".join(rows[:3] + ["0 0 0\n"] + rows[4:]))],
                        ["hdr.txt", "line 7", "face 3", "the direction is zero"])
        self.expect_bad([self.cube, "--field", self.write("cols.txt", header + "".join(rows[:2] + ["1 0\n"] + rows[3:]))],
                        ["cols.txt", "line 6", "face 2", "expected 3 numbers"])
        bom = self.write("bom.txt", "\ufeff" + "".join(rows))
        self.assertEqual(self.gparam(self.cube, "--field", bom)["status"], "solved")
        # Huge and tiny directions are directions (their norm over- or underflowed: "zero").
        huge = self.write("huge.txt", "".join(" ".join(f"{1e307 * float(x):.17g}" for x in r.split()) + "\n" for r in rows))
        self.assertEqual(self.gparam(self.cube, "--field", huge)["status"], "solved")
        # No output may name an input: it would be destroyed (exit 0 before, the mesh replaced by JSON).
        with open(self.cube) as f:
            cube_text = f.read()
        for args, needle in (([self.cube, "--summary", self.cube], "--summary"),
                             ([self.cube, "--field", field, "--field-out", field], "--field-out"),
                             ([self.cube, "-o", self.cube], "--output"),
                             ([self.cube, "--distortion", self.cube], "--distortion")):
            p = run("gparam", *args, check_code=1)
            self.assertIn(needle, p.stderr)
            self.assertIn("is the input mesh" if needle != "--field-out" else "is the --field file", p.stderr)
        with open(self.cube) as f:
            self.assertEqual(f.read(), cube_text)
        with open(field) as f:
            self.assertEqual([l for l in f if l.strip()], rows)
        _, nv = cube_obj()
        flat = ["6.283185307179586\n"] * nv
        self.expect_bad([self.cube, "--cones", self.write("flat.txt", "".join(flat))],
                        ["flat.txt", "add up to 0/4", "Euler characteristic 2"])
        self.expect_bad([self.cube, "--cones", self.write("odd.txt", "".join(["1.0\n"] + flat[1:]))],
                        ["odd.txt", "line 1", "quarter turns"])
        self.expect_bad([self.cube, "--cones", self.write("few.txt", "".join(flat[1:]))], ["few.txt", "angles for"])
        self.expect_bad([self.cube, "--cones", self.out("flat.txt"), "--field", "unit"], ["--cones", "not both"])

    def test_outputs_that_would_clobber_each_other(self):
        """'-' is stdout for --summary and --distortion only (--cones-out - and --field-out -
        wrote a file named '-'); the --report folder's own files are no other output's (the
        report replaced them: a distortion file became the report's summary.json, exit 0); a
        report folder that cannot be made is refused before the solve (it failed after the
        other outputs were written); the report's summary.json is --summary's (it lacked the
        version and kernels, and replaced --summary DIR/summary.json so)."""
        cwd = os.getcwd()
        os.chdir(self.dir)
        try:
            for flag in ("--cones-out", "--field-out"):
                self.expect_bad([self.cube, flag, "-"], [flag + " -", "give a file name"])
                self.assertFalse(os.path.exists(os.path.join(self.dir, "-")), flag)
        finally:
            os.chdir(cwd)
        report = self.out("rep")
        os.mkdir(report)
        for flag, name in (("--distortion", "summary.json"), ("--cones-out", "index.html"),
                           ("--field-out", "l2_field.png"), ("--field-out", "view-uv.svg")):
            self.expect_bad([self.cube, "--report", report + "/", flag, os.path.join(report, name)],
                            [flag, name, "the --report folder's own"])
        self.assertEqual(os.listdir(report), [])
        self.expect_bad([self.cube, "--report", self.out("bad.obj")], ["--output", "is the --report folder"])
        plain = self.write("plain.txt", "not a folder\n")
        self.expect_bad([self.cube, "--report", os.path.join(plain, "rep")], ["--report", "plain.txt is a file"])
        with open(plain) as f:
            self.assertEqual(f.read(), "not a folder\n")
        summary = os.path.join(report, "summary.json")
        run("gparam", self.cube, "--report", report, "--summary", summary, "--cones-out",
            os.path.join(report, "cones.txt"), "--quiet")
        with open(summary) as f:
            s = json.load(f)
        self.assertIn("version", s)
        self.assertIn("blas_kernels", s)
        self.assertTrue(os.path.exists(os.path.join(report, "cones.txt")))

    def test_arap_relax_and_extrapolation_off(self):
        # --measure arap --method relax on a seamed surface (it failed after its linf start);
        # --lg-extrapolation 0 turns the extrapolation off (it was refused). A cube with its
        # vertices moved a little (deterministically), so that there is distortion to spread.
        lines, _ = cube_obj(n=4)
        bumpy, k = [], 0
        for l in lines:
            if l.startswith("v "):
                x, y, z = (float(t) for t in l.split()[1:])
                k += 1
                x, y, z = (c + 0.05 * math.sin(7.3 * k + i) for i, c in enumerate((x, y, z)))
                l = f"v {x} {y} {z}"
            bumpy.append(l)
        mesh = self.write("bumpy.obj", "\n".join(bumpy) + "\n")
        linf = self.gparam(mesh, "--measure", "arap", "--method", "linf")
        for extra in ([], ["--lg-extrapolation", "0"]):
            s = self.gparam(mesh, "-o", self.out("arap.obj"), "--measure", "arap", "--method", "relax",
                            "--sweeps", "5", *extra)
            self.assertEqual(s["status"], "solved", s.get("message"))
            self.assertEqual(s["sweeps"], 5)
            self.assertGreater(s["local_global_iterations"], 5)  # the linf start's steps, then the sweeps
            self.assertLess(s["seam_error"], 1e-9)
            self.assertGreater(s["max_distortion"], 1e-3)
            self.assertLessEqual(s["max_distortion"], linf["max_distortion"] * (1 + 1e-9))

    def test_cow_relax_report(self):
        cow = os.path.join(DATA, "closed", "cow.obj")
        if not os.path.exists(cow):
            self.skipTest(f"no {cow}")
        report = self.out("R")
        s = self.gparam(cow, "-o", self.out("cow.obj"), "--method", "relax", "--sweeps", "10", "--report", report,
                        code=None)
        self.assertEqual(s["euler_characteristic"], 2)
        self.assertEqual(sum(x["index"] for x in s["singularity_indices"]), 8)
        self.assertLess(s["seam_error"], 1e-9)
        for name in ("index.html", "relax_field.png", "relax_grid.png", "summary.json"):
            self.assertTrue(os.path.exists(os.path.join(report, name)), name)


if __name__ == "__main__":
    if not os.path.exists(CLI) and os.sep in CLI:
        print(f"no strictmin at {CLI}", file=sys.stderr)
        sys.exit(77)
    unittest.main()
