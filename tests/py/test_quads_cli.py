"""End-to-end tests of quad extraction (docs/gparam.md, "Quad meshes"): `strictmin quads`
and `gparam --quad-mesh` on the cube's integer-grid map (its exact grid, exit 0), a map
with flipped triangles (holes, exit 2, the quads kept written), and bad input (exit 1, a
message naming the problem, no output file). Run by ctest with STRICTMIN_CLI set."""
import json
import os
import subprocess
import time
import unittest

from cli_support import CLI, DATA, run
from test_gparam_cli import CubeCase, cube_obj, edge_aligned_field


def read_obj(path):
    V, faces, vts = [], [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if p and p[0] == "v":
                V.append([float(x) for x in p[1:4]])
            elif p and p[0] == "vt":
                vts.append([float(x) for x in p[1:3]])
            elif p and p[0] == "f":
                faces.append([[int(i) - 1 for i in c.split("/")] for c in p[1:]])
    return V, vts, faces


class Quads(CubeCase):
    def setUp(self):
        super().setUp()
        lines, _ = cube_obj()  # side 2, 3 by 3 cells a side
        self.field = self.write("edges.txt", edge_aligned_field(lines))

    def grid_map(self, *extra, code=0):
        summary = self.out("gparam.json")
        run("gparam", self.cube, "-o", self.out("map.obj"), "--field", self.field, "--edge-length", "0.5",
            "--integer-grid", "--summary", summary, "--quiet", *extra, check_code=code)
        with open(summary) as f:
            return json.load(f)

    def quads(self, map_path, code):
        summary = self.out("quads.json")
        p = run("quads", map_path, "-o", self.out("quads.obj"), "--summary", summary, check_code=code)
        with open(summary) as f:
            return json.load(f), p

    def test_the_cube_gives_its_grid(self):
        # Side 2 at h = 0.5: 6 x 16 quads, 6 x 9 + 12 x 3 + 8 vertices, the 8 corners of valence 3.
        s = self.grid_map("--quad-mesh", self.out("gq.obj"))
        q = s["quad_mesh"]
        self.assertEqual(q["status"], "complete")
        self.assertEqual(q["file"], self.out("gq.obj"))
        self.assertEqual((q["quads"], q["vertices"], q["euler_characteristic"]), (96, 98, 2))
        self.assertEqual(q["valences"], {"3": 8, "4": 90})
        self.assertEqual(q["holes"] + q["dropped_squares"] + q["boundary_edges"], 0)
        V, vts, faces = read_obj(self.out("gq.obj"))
        self.assertEqual((len(V), len(faces)), (98, 96))
        for face in faces:
            self.assertEqual(len(face), 4)
            for v, t in face:
                self.assertTrue(all(abs(2 * x - round(2 * x)) < 1e-9 for x in V[v]), V[v])
                self.assertTrue(all(x == round(x) for x in vts[t]), vts[t])
        # strictmin quads on the written map: the same quad mesh, file for file.
        s2, p = self.quads(self.out("map.obj"), 0)
        self.assertEqual(s2["task"], "quads")
        self.assertEqual(s2["input"], self.out("map.obj"))
        self.assertEqual((s2["status"], s2["quads"], s2["vertices"]), ("complete", 96, 98))
        self.assertIn("96 quads", p.stderr)
        with open(self.out("gq.obj")) as a, open(self.out("quads.obj")) as b:
            self.assertEqual(a.read(), b.read())

    def test_report_draws_the_quads(self):
        report = self.out("report")
        self.grid_map("--quad-mesh", self.out("gq.obj"), "--report", report)
        self.assertTrue(os.path.getsize(os.path.join(report, "l2_quads.png")) > 1000)
        with open(os.path.join(report, "index.html")) as f:
            self.assertIn("l2_quads.png", f.read())
        # Without --quad-mesh there is no quad picture.
        report2 = self.out("report2")
        self.grid_map("--report", report2)
        self.assertFalse(os.path.exists(os.path.join(report2, "l2_quads.png")))

    def test_flips_leave_holes_and_exit_2(self):
        self.grid_map()
        # Move one vertex away from the seams by more than a grid unit: its triangles fold over,
        # and the map stays seamless and on the grid.
        with open(self.out("map.obj")) as f:
            lines = f.read().split("\n")
        vt_lines = [i for i, l in enumerate(lines) if l.startswith("vt ")]
        uses = {}
        for l in lines:
            if l.startswith("f "):
                for c in l.split()[1:]:
                    v, t = (int(x) for x in c.split("/"))
                    uses.setdefault(v, set()).add(t)
        neighbours = {}
        for l in lines:
            if l.startswith("f "):
                vs = [int(c.split("/")[0]) for c in l.split()[1:]]
                for a in vs:
                    neighbours.setdefault(a, set()).update(vs)
        # No seam reaches it: it and its neighbours have one vt each (a cone at a seam's end has one too).
        v = next(v for v in sorted(uses) if all(len(uses[x]) == 1 for x in neighbours[v]))
        t = next(iter(uses[v]))
        u, w = (float(x) for x in lines[vt_lines[t - 1]].split()[1:])
        lines[vt_lines[t - 1]] = f"vt {u + 1.7} {w + 0.9}"
        folded = self.write("folded.obj", "\n".join(lines))
        s, p = self.quads(folded, 2)
        self.assertEqual(s["status"], "holes")
        self.assertGreater(s["flipped_triangles"], 0)
        self.assertGreater(s["squares_touching_flips"], 0)
        self.assertGreaterEqual(s["holes"], 1)
        self.assertEqual(s["non_manifold_edges"], 0)
        self.assertIn("hole", p.stderr)
        V, _, faces = read_obj(self.out("quads.obj"))
        self.assertEqual(len(faces), s["quads"])
        self.assertLess(s["quads"], 96)
        # --fill-holes: this hole is away from the cones, and is filled with the grid's squares
        # (exit 0, status "filled"): the cube's 96 quads again.
        summary = self.out("filled.json")
        p = run("quads", folded, "-o", self.out("filled.obj"), "--fill-holes", "--summary", summary, check_code=0)
        with open(summary) as f:
            s2 = json.load(f)
        self.assertTrue(s2["fill_holes"])
        self.assertEqual(s2["status"], "filled")
        self.assertEqual((s2["quads"], s2["holes"], s2["euler_characteristic"]), (96, 0, 2))
        self.assertEqual(s2["filled_squares"] + s["quads"], s2["quads"])
        self.assertIn("complete after filling", p.stderr)
        self.assertEqual(len(read_obj(self.out("filled.obj"))[2]), 96)

    def test_sigterm_stops_a_long_extraction(self):
        # The cube's map scaled by 300: an integer-grid map of 96 x 300^2 = 8.6e6 squares, long
        # enough to be stopped: exit 130, no output file (the extraction checks for interrupts).
        self.grid_map()
        with open(self.out("map.obj")) as f:
            lines = f.read().split("\n")
        scaled = []
        for l in lines:
            if l.startswith("vt "):
                u, v = (float(x) for x in l.split()[1:3])
                l = f"vt {u * 300!r} {v * 300!r}"
            scaled.append(l)
        big = self.write("big.obj", "\n".join(scaled))
        p = subprocess.Popen([CLI, "quads", big, "-o", self.out("big_quads.obj")], stderr=subprocess.PIPE, text=True)
        time.sleep(1.5)
        p.terminate()
        self.assertEqual(p.wait(timeout=60), 130, p.stderr.read())
        self.assertFalse(os.path.exists(self.out("big_quads.obj")))

    def test_no_quad_folds_onto_another(self):
        # Cow at 1000 quads has folds around close cones. A square whose corner came from another
        # layer of a fold was kept: it faced against the surface (normal . surface -0.68) and
        # shared a diagonal with its neighbour (the same surface point at (7, -17) in one and
        # (9, -17) in the other), with 0 non-manifold edges reported. Checked here from the
        # OBJs alone: no two quads share three corners or a diagonal, every quad faces with
        # the triangles nearest it, and no vertex is pinched.
        import numpy as np
        cow = os.path.join(DATA, "closed", "cow.obj")
        if not os.path.exists(cow):
            self.skipTest(f"no {cow}")
        summary = self.out("cow.json")
        run("gparam", cow, "--integer-grid", "--quads", "1000", "--method", "linf", "-o", self.out("cow_uv.obj"),
            "--quad-mesh", self.out("cow_quads.obj"), "--summary", summary, "--quiet", check_code=2)
        with open(summary) as f:
            q = json.load(f)["quad_mesh"]
        self.assertEqual(q["status"], "holes")
        self.assertIn("hole(s)", q["reason"])
        self.assertGreaterEqual(q["squares_inverted"] + q["squares_overlapping"], 1)
        V, _, faces = read_obj(self.out("cow_quads.obj"))
        quads = [[c[0] for c in face] for face in faces]
        self.assertEqual(len(quads), q["quads"])
        at = {}
        for i, quad in enumerate(quads):
            for v in quad:
                at.setdefault(v, []).append(i)
        for i, a in enumerate(quads):
            for j in {j for v in a for j in at[v] if j > i}:
                b = quads[j]
                shared = [k for k in range(4) if a[k] in b]
                if len(shared) == 2:  # a side of both: consecutive in a and in b
                    k0, k1 = shared
                    self.assertIn((k1 - k0) % 4, (1, 3), (i, j))
                    self.assertIn((b.index(a[k1]) - b.index(a[k0])) % 4, (1, 3), (i, j))
                else:
                    self.assertLessEqual(len(shared), 1, (i, j))
        Vs, _, Fs = read_obj(cow)
        Vs, Fs = np.array(Vs), np.array([[c[0] for c in f] for f in Fs])
        centres = Vs[Fs].mean(axis=1)
        normals = np.cross(Vs[Fs[:, 1]] - Vs[Fs[:, 0]], Vs[Fs[:, 2]] - Vs[Fs[:, 0]])
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        Vq = np.array(V)
        for i, quad in enumerate(quads):
            p = Vq[quad]
            near = np.argsort(np.linalg.norm(centres - p.mean(axis=0), axis=1))[:6]
            self.assertGreater(np.cross(p[2] - p[0], p[3] - p[1]) @ normals[near].sum(axis=0), 0, f"quad {i}")
        fans_split = 0
        for v, around in at.items():  # quads around v, joined through the edges at v
            group = {i: i for i in around}
            def find(i):
                while group[i] != i:
                    i = group[i]
                return i
            first_with = {}
            for i in around:
                k = quads[i].index(v)
                for w in (quads[i][(k + 1) % 4], quads[i][(k + 3) % 4]):
                    if w in first_with:
                        group[find(i)] = find(first_with[w])
                    else:
                        first_with[w] = i
            fans_split += len({find(i) for i in around}) > 1
        # Pinched vertices are split (each fan after the first gets its own copy, at the same
        # point): the OBJ has none left, and each copy shares its original's position.
        self.assertEqual(fans_split, 0)
        self.assertEqual(q["non_manifold_vertices"], 0)
        self.assertGreaterEqual(q["split_vertices"], 1)  # (4 measured)
        positions = {}
        for v in V:
            positions[tuple(v)] = positions.get(tuple(v), 0) + 1
        self.assertEqual(sum(n - 1 for n in positions.values()), q["split_vertices"])

    def test_a_map_too_fine_is_not_extracted_and_no_earlier_file_stays(self):
        # --quads 2e7: more squares than the extraction takes. The reason is said in gparam's
        # terms (it asked whether the UVs were in grid units), and a quad mesh left at the path
        # by an earlier run is removed (it stayed, passing for this run's).
        earlier = self.write("q.obj", "v 0 0 0\n")
        summary = self.out("fine.json")
        p = run("gparam", self.cube, "-o", self.out("fine.obj"), "--field", self.field, "--quads", "20000000",
                "--integer-grid", "--quad-mesh", earlier, "--summary", summary, check_code=2)
        with open(summary) as f:
            q = json.load(f)["quad_mesh"]
        self.assertEqual(q["status"], "not-extracted")
        self.assertIn("unit squares (--quads / --edge-length), more than quad extraction takes", q["reason"])
        self.assertNotIn("grid units", q["reason"])
        self.assertEqual(q["removed_earlier_file"], earlier)
        self.assertFalse(os.path.exists(earlier))
        self.assertIn("not-extracted", p.stderr)

    def test_messages_name_the_problem(self):
        # An unused vertex in a map given to quads: the message spoke of "a global
        # parametrization"; eval of a map whose elements run the other way said "different
        # vertices".
        self.grid_map()
        with open(self.out("map.obj")) as f:
            lines = f.read().split("\n")
        first_v = next(i for i, l in enumerate(lines) if l.startswith("v "))
        lines.insert(first_v, "v 9 9 9")
        shifted = []
        for l in lines:
            if l.startswith("f "):
                l = "f " + " ".join("/".join([str(int(c.split("/")[0]) + 1)] + c.split("/")[1:]) for c in l.split()[1:])
            shifted.append(l)
        unused = self.write("unused.obj", "\n".join(shifted))
        p = run("quads", unused, "-o", self.out("u.obj"), check_code=1)
        self.assertIn("vertex 0 (0-based) belongs to no face: remove the unused vertices", p.stderr)
        self.assertNotIn("global parametrization", p.stderr)
        with open(self.cube) as f:
            cube_lines = f.read().split("\n")
        rev = self.write("rev.obj", "\n".join(
            "f " + " ".join(reversed(l.split()[1:])) if l.startswith("f ") else l for l in cube_lines))
        p = run("eval", self.cube, rev, check_code=1)
        self.assertIn("element 0 (0-based) has its vertices in the reverse order (another orientation)", p.stderr)
        # The same triangle from another corner is told apart from a reversed one.
        rot = self.write("rot.obj", "\n".join(
            "f " + " ".join(l.split()[2:] + l.split()[1:2]) if l.startswith("f ") else l for l in cube_lines))
        p = run("eval", self.cube, rot, check_code=1)
        self.assertIn("element 0 (0-based) lists its vertices from another corner (the same orientation)", p.stderr)

    def test_a_collapsed_map_is_incomplete_without_holes(self):
        # Every vt the same integer point: seamless and on the grid, every triangle of zero UV
        # area, no square at all. Exit 2, and the message says why rather than "0 hole(s)".
        self.grid_map()
        with open(self.out("map.obj")) as f:
            lines = ["vt 3 3" if l.startswith("vt ") else l for l in f.read().split("\n")]
        collapsed = self.write("collapsed.obj", "\n".join(lines))
        s, p = self.quads(collapsed, 2)
        self.assertEqual((s["status"], s["quads"], s["holes"]), ("holes", 0, 0))
        self.assertIn("incomplete", s["reason"])
        self.assertNotIn("0 hole(s)", p.stderr)
        self.assertIn("incomplete", p.stderr)
        self.assertIn("the surface's Euler characteristic is 2", p.stderr)
        self.assertIn("flipped triangles", p.stderr)

    def assert_refused(self, args, words, outputs):
        p = run(*args, check_code=1)
        for w in words:
            self.assertIn(w, p.stderr)
        for o in outputs:
            self.assertFalse(os.path.exists(o), o)

    def test_bad_input(self):
        q, s = self.out("q.obj"), self.out("s.json")
        # No vt.
        self.assert_refused(["quads", self.cube, "-o", q, "--summary", s], ["cube.obj", "no per-corner UVs"], [q, s])
        # A seamless map off the grid (no --integer-grid, h = 0.7).
        run("gparam", self.cube, "-o", self.out("free.obj"), "--field", self.field, "--edge-length", "0.7",
            "--quiet", check_code=0)
        self.assert_refused(["quads", self.out("free.obj"), "-o", q, "--summary", s],
                            ["free.obj", "misses a pair of integers"], [q, s])
        # Only OBJ is written; gparam's quads need the integer grid.
        self.grid_map()
        self.assert_refused(["quads", self.out("map.obj"), "-o", self.out("q.off")], ["q.off", ".obj only"],
                            [self.out("q.off")])
        g = self.out("g.obj")
        self.assert_refused(["gparam", self.cube, "-o", g, "--quad-mesh", q], ["--quad-mesh", "--integer-grid"], [g, q])
        self.assert_refused(["gparam", self.cube, "-o", g, "--integer-grid", "--quad-mesh", self.out("q.ply")],
                            ["q.ply", ".obj only"], [g, self.out("q.ply")])
        self.assert_refused(["quads", self.out("map.obj"), "--tolerance", "0.5"], ["--tolerance"], [])
        self.assert_refused(["gparam", self.cube, "-o", g, "--integer-grid", "--fill-holes"],
                            ["--fill-holes", "--quad-mesh"], [g])
        # One face without vt: the reader drops them all, and the message says why (also when quiet).
        with open(self.out("map.obj")) as f:
            lines = f.read().splitlines()
        first = next(i for i, line in enumerate(lines) if line.startswith("f "))
        lines[first] = "f " + " ".join(c.split("/")[0] for c in lines[first].split()[1:])
        partial = self.write("partial.obj", "\n".join(lines) + "\n")
        self.assert_refused(["quads", partial, "-o", q, "--summary", s, "--quiet"],
                            ["partial.obj", "no per-corner UVs", "only", "faces have them"], [q, s])


if __name__ == "__main__":
    unittest.main()
