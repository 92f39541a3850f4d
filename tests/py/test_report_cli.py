"""End-to-end tests of the report commands: `deform --report DIR` and `strictmin report DIR
--run SUMMARY ...` on results written by deform. Run by ctest with STRICTMIN_CLI pointing
at the built tool."""
import json
import os
import re
import tempfile
import unittest

import cli_support
from cli_support import CLI
from test_gparam_cli import cube_obj


def run(*args, cwd=None, check_code=0):
    return cli_support.run(*args, cwd=cwd, check_code=check_code)


def read(path, mode="r"):
    with open(path, mode, **({} if "b" in mode else {"encoding": "utf-8"})) as f:
        return f.read()


def references(html):
    return [r for r in re.findall(r'(?:src|href)="([^"]*)"', html) if not r.startswith("#")]


class Report(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def check_folder(self, folder):
        html = read(os.path.join(folder, "index.html"))
        for ref in references(html):
            self.assertNotIn(":", ref, "relative links only")
            self.assertTrue(os.path.exists(os.path.join(folder, ref)), ref)
        self.assertNotIn("<script", html)
        return html

    def test_deform_report(self):
        out = os.path.join(self.dir, "r")
        run("deform", "--example", "square", "--method", "l2", "--report", out, "--quiet")
        for name in ("summary.json", "histogram.svg", "view.svg", "index.html"):
            self.assertTrue(os.path.exists(os.path.join(out, name)), name)
        s = json.loads(read(os.path.join(out, "summary.json")))
        self.assertEqual(s["method"], "l2")
        self.assertIn("distortion_file", s)
        html = self.check_folder(out)
        self.assertIn("L2 (least squares)", html)
        self.assertEqual(read(os.path.join(out, "view.svg")).count("<polygon"), 800)

    def test_deform_report_of_tets_is_a_png(self):
        out = os.path.join(self.dir, "t")
        run("deform", "--example", "tetbar", "--method", "l2", "--report", out, "--report-scale", "2", "--quiet")
        self.assertEqual(read(os.path.join(out, "view.png"), "rb")[:8], b"\x89PNG\r\n\x1a\n")
        self.assertIn("red = 2 and above", self.check_folder(out))

    def test_report_compares_results_already_computed(self):
        for method in ("l2", "linf"):
            run("deform", "--example", "square", "--method", method, "-o", f"{method}.obj", "--distortion",
                f"{method}.txt", "--summary", f"{method}.json", "--quiet", cwd=self.dir)
            s = json.loads(read(os.path.join(self.dir, f"{method}.json")))
            self.assertEqual(s["distortion_file"], f"{method}.txt")
        p = run("report", "out", "--run", "l2.json", "--run", "linf.json", "--scale", "0.5", cwd=self.dir)
        self.assertIn("index.html", p.stdout)
        out = os.path.join(self.dir, "out")
        html = self.check_folder(out)
        self.assertIn("L\u221e (least maximum) is less distorting than L2 (least squares)", html)
        self.assertIn("red = 0.5 and above", html)
        for name in ("l2.svg", "linf.svg", "histogram.svg", "l2.json", "linf.json"):
            self.assertTrue(os.path.exists(os.path.join(out, "square", name)), name)

    def test_direct_is_compared_at_its_delta_k(self):
        # direct fixes each level's elements within delta-k of it (1e-3 here): on the square it
        # has more triangles than L-infinity within 1e-5 of the maximum 0.3 and fewer within
        # 1e-3. The verdict ties values at delta-k (it said L-infinity was less distorting).
        for method in ("linf", "direct"):
            run("deform", "--example", "square", "--method", method, "-o", f"{method}.obj", "--distortion",
                f"{method}.txt", "--summary", f"{method}.json", "--quiet", cwd=self.dir)
        s = json.loads(read(os.path.join(self.dir, "direct.json")))
        self.assertEqual(s["delta_k"], 1e-3)
        self.assertEqual(s["k_min"], 0.1)
        run("report", "out", "linf.json", "direct.json", cwd=self.dir)
        html = read(os.path.join(self.dir, "out", "index.html"))
        self.assertIn("strict minimizer (direct) is less distorting than L\u221e (least maximum)", html)
        self.assertIn("values within 0.001, direct&#39;s delta-k, count as equal", html)

    def test_a_report_cut_short_leaves_no_index(self):
        """The index is written last and the previous one is removed first, so a report whose
        writing stopped (here an error; a second Ctrl-C alike) has no index.html: the older
        run's index stayed and pointed at a mix of both runs' files."""
        out = os.path.join(self.dir, "R")
        run("deform", "--example", "square", "--method", "l2", "--report", out, "--quiet")
        self.assertTrue(os.path.exists(os.path.join(out, "index.html")))
        os.remove(os.path.join(out, "histogram.svg"))
        os.mkdir(os.path.join(out, "histogram.svg"))  # the next report cannot write it
        p = run("deform", "--example", "square", "--method", "linf", "--report", out, "--quiet", check_code=1)
        self.assertIn("histogram.svg", p.stderr)
        self.assertFalse(os.path.exists(os.path.join(out, "index.html")))

    def test_report_reads_results_with_carriage_returns_alone(self):
        """A result rewritten with CR-only line ends (the classic Mac convention) gives the
        same picture: its OBJ was read as one line ("no vertices found")."""
        for method in ("l2", "linf"):
            run("deform", "--example", "square", "--method", method, "-o", f"{method}.obj", "--distortion",
                f"{method}.txt", "--summary", f"{method}.json", "--quiet", cwd=self.dir)
        run("report", "lf", "--run", "l2.json", "--run", "linf.json", cwd=self.dir)
        for method in ("l2", "linf"):
            path = os.path.join(self.dir, f"{method}.obj")
            text = read(path, "rb").replace(b"\n", b"\r")
            with open(path, "wb") as f:
                f.write(text)
        run("report", "cr", "--run", "l2.json", "--run", "linf.json", cwd=self.dir)
        for name in ("l2.svg", "linf.svg"):
            self.assertEqual(read(os.path.join(self.dir, "cr", "square", name)),
                             read(os.path.join(self.dir, "lf", "square", name)), name)

    def test_report_of_the_demos_results(self):
        """docs/report.md: the demo writes each result's summary, map and distortion for
        `strictmin report`; its param and gparam summaries (inputs example:spherical-cap and
        example:bulged-frame) were refused as unknown examples (exit 1). The gparam-boundary
        section (example:bulged-frame-window) maps a surface with boundary."""
        demo = os.path.join(self.dir, "demo")
        run("demo", "--out", demo, "--quiet", check_code=0)
        for section in ("square", "param", "gparam", "gparam-boundary"):
            summaries = [os.path.join(demo, section, f"{m}.json") for m in ("l2", "linf", "relax")]
            out = os.path.join(self.dir, "again_" + section)
            run("report", out, *summaries, "--quiet", check_code=0)
            html = self.check_folder(out)
            self.assertIn("3 results for input example:", html)
            self.assertTrue(any(name.startswith("input.") for _, _, files in os.walk(out) for name in files),
                            section + ": the rest surface is drawn")
        # The gparam section's integer-grid map and its quad mesh (docs/gparam.md, "Quad meshes").
        for name in ("grid.obj", "quads.obj", "quads.png"):
            self.assertTrue(os.path.getsize(os.path.join(demo, "gparam", name)) > 0, name)
        with open(os.path.join(demo, "index.html")) as f:
            self.assertIn("gparam/quads.png", f.read())
        # The surface with boundary: genus 1 with one loop, the window's 4 reflex corners at -1/4
        # beside the frame's 16 corners; every method seamless, without flips, and relax and
        # linf below l2.
        boundary = {}
        for m in ("l2", "linf", "relax"):
            with open(os.path.join(demo, "gparam-boundary", f"{m}.json")) as f:
                boundary[m] = json.load(f)
        for method, s in boundary.items():
            self.assertEqual(s["boundary_loops"], 1, method)
            self.assertEqual(s["euler_characteristic"], -1, method)
            self.assertEqual(sum(x["index"] for x in s["singularity_indices"]), -4, method)
            self.assertEqual(sum(1 for x in s["singularity_indices"] if x.get("boundary")), 4, method)
            self.assertLess(s["seam_error"], 1e-9, method)
            self.assertEqual(s["flipped"], 0, method)
            self.assertEqual(s["warnings"], [], method)
        self.assertLess(boundary["linf"]["max_distortion"], boundary["l2"]["max_distortion"])
        self.assertLessEqual(boundary["relax"]["max_distortion"], boundary["linf"]["max_distortion"] + 1e-4)

    def test_a_report_into_an_earlier_ones_folder_removes_its_stale_files(self):
        # The pictures of a run no longer in the report stayed beside the new index.html.
        for method in ("l2", "linf"):
            run("deform", "--example", "square", "--method", method, "-o", f"{method}.obj", "--distortion",
                f"{method}.txt", "--summary", f"{method}.json", "--quiet", cwd=self.dir)
        out = os.path.join(self.dir, "out")
        run("report", "out", "--run", "l2.json", "--run", "linf.json", cwd=self.dir)
        stale = [os.path.join(out, "square", name) for name in ("linf.svg", "linf-histogram.svg", "linf.json")]
        for path in stale:
            self.assertTrue(os.path.exists(path), path)
        cli_support.write(os.path.join(out, "notes.txt"), "mine\n")
        cli_support.write(os.path.join(out, "square", "notes.txt"), "mine\n")
        cli_support.write(os.path.join(self.dir, "keep.txt"), "mine\n")
        with open(os.path.join(out, ".strictmin-report"), "a", encoding="utf-8") as f:
            f.write("../keep.txt\n" + os.path.join(self.dir, "keep.txt") + "\n")  # never outside the folder
        run("report", "out", "--run", "l2.json", cwd=self.dir)
        for path in stale:
            self.assertFalse(os.path.exists(path), path)
        self.check_folder(out)
        for path in (os.path.join(out, "notes.txt"), os.path.join(out, "square", "notes.txt"),
                     os.path.join(self.dir, "keep.txt"), os.path.join(out, "square", "l2.svg")):
            self.assertTrue(os.path.exists(path), path)
        listed = read(os.path.join(out, ".strictmin-report")).split()
        self.assertIn("index.html", listed)
        self.assertIn("square/l2.svg", listed)
        self.assertNotIn("../keep.txt", listed)
        # A task's --report into that folder: the comparison's section goes, the user's files stay.
        run("deform", "--example", "square", "--method", "l2", "--report", out, "--quiet")
        self.assertFalse(os.path.exists(os.path.join(out, "square", "l2.svg")))
        self.assertTrue(os.path.exists(os.path.join(out, "square", "notes.txt")))
        self.assertTrue(os.path.exists(os.path.join(out, "view.svg")))
        self.check_folder(out)

    def test_only_runs_of_one_problem_are_compared(self):
        # An ARAP run was ranked against fd runs ("L-inf is less distorting than L-inf"), two
        # meshes named m.obj in two folders shared a section, and a capped solve read as its
        # method's answer.
        def deform(name, *extra, cwd=None):
            run("deform", "--example", "square", "-o", f"{name}.obj", "--distortion", f"{name}.txt", "--summary",
                f"{name}.json", "--quiet", *extra, cwd=cwd or self.dir, check_code=None)
        deform("l2", "--method", "l2")
        deform("linf", "--method", "linf")
        deform("capped", "--method", "linf", "--max-iterations", "2")
        deform("arap", "--method", "linf", "--measure", "arap")
        p = run("report", "out", "l2.json", "linf.json", "capped.json", "arap.json", cwd=self.dir, check_code=2)
        html = self.check_folder(os.path.join(self.dir, "out"))
        sections = re.findall(r"<h2[^>]*>(.*?)</h2>", html)
        self.assertEqual(len(sections), 2, sections)
        self.assertTrue(any("measure arap" in s for s in sections), sections)
        self.assertTrue(any("measure fd" in s for s in sections), sections)
        self.assertNotIn("is less distorting than L∞ (least maximum) (arap", html)
        self.assertIn("L∞ (least maximum) (capped.json) (not solved: max-iterations)", html)
        self.assertIn("L∞ (least maximum) (linf.json)", html)  # both runs of linf named by their files
        # Two files named m.obj: two sections, titled by their paths.
        square = "v 0 0\nv 1 0\nv 1 1\nv 0 1\nv 0.5 0.5\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"
        strip = "v 0 0\nv 2 0\nv 2 1\nv 0 1\nv 1 0.5\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"
        for folder, mesh in (("A", square), ("B", strip)):
            os.makedirs(os.path.join(self.dir, folder))
            cli_support.write(os.path.join(self.dir, folder, "m.obj"), mesh)
            cli_support.write(os.path.join(self.dir, folder, "h.txt"), "0 0 0\n2 2.2 1.1\n")
            run("deform", "m.obj", "--handles", "h.txt", "--method", "linf", "-o", "o.obj", "--distortion", "d.txt",
                "--summary", "s.json", "--quiet", cwd=os.path.join(self.dir, folder))
        run("report", "two", os.path.join("A", "s.json"), os.path.join("B", "s.json"), cwd=self.dir)
        html = read(os.path.join(self.dir, "two", "index.html"))
        sections = re.findall(r"<h2[^>]*>(.*?)</h2>", html)
        self.assertEqual(len(sections), 2, sections)
        self.assertTrue(sections[0].endswith(os.path.join("A", "m.obj")) and sections[1].endswith(os.path.join("B", "m.obj")),
                        sections)
        # One method run twice with summaries of one name in two folders: named by their paths
        # (both were "L∞ (least maximum) (linf.json)").
        os.makedirs(os.path.join(self.dir, "again"))
        deform("linf", "--method", "linf", "--gap", "1e-6", cwd=os.path.join(self.dir, "again"))
        run("report", "dup", "linf.json", os.path.join("again", "linf.json"), cwd=self.dir)
        html = read(os.path.join(self.dir, "dup", "index.html"))
        self.assertIn("L∞ (least maximum) (linf.json)", html)
        self.assertIn("L∞ (least maximum) (" + os.path.join("again", "linf.json") + ")", html)

    def test_zero_distortion_is_said_plainly(self):
        # An exact map (1e-14 from rounding) gave "inf x the least maximum 0" and a histogram of noise.
        grid = "".join(f"v {x} {y}\n" for y in range(4) for x in range(4))
        grid += "".join(f"f {1 + x + 4 * y} {2 + x + 4 * y} {6 + x + 4 * y}\nf {1 + x + 4 * y} {6 + x + 4 * y} {5 + x + 4 * y}\n"
                        for y in range(3) for x in range(3))
        cli_support.write(os.path.join(self.dir, "g.obj"), grid)
        cli_support.write(os.path.join(self.dir, "h.txt"), "0 0.5 0.25\n15 3.5 3.25\n")  # a translation
        for m in ("l2", "linf"):
            run("deform", "g.obj", "--handles", "h.txt", "--method", m, "-o", f"{m}.obj", "--distortion", f"{m}.txt",
                "--summary", f"{m}.json", "--quiet", cwd=self.dir)
        # Distortions are norms: the certified bound of a map of zero distortion is 0, not -4e-30.
        with open(os.path.join(self.dir, "linf.json")) as f:
            self.assertGreaterEqual(json.load(f)["lower_bound"], 0.0)
        run("report", "z", "l2.json", "linf.json", cwd=self.dir)
        html = read(os.path.join(self.dir, "z", "index.html"))
        self.assertIn("no distortion (maximum", html)
        self.assertNotIn("inf\u00d7", html)
        self.assertNotIn("the least maximum 0", html)
        svg = read(os.path.join(self.dir, "z", "g-obj", "histogram.svg"))
        self.assertNotIn("e-14", svg)

    def test_summary_is_checked_against_its_files(self):
        # A summary whose figures disagree with its own map and distortion file is refused by
        # name: it put "certified lower bound 0.7" beside a maximum of 0.3, an element count in
        # a second section with the same title, and a negative "qc" distortion on the page.
        run("deform", "--example", "square", "--method", "linf", "-o", "sq.obj", "--distortion", "sq.txt",
            "--summary", "sq.json", "--quiet", cwd=self.dir, check_code=0)
        summary = json.loads(read(os.path.join(self.dir, "sq.json")))
        for key, value, needle in (("lower_bound", 0.7, "is above the map's own maximum"),
                                   ("elements", 999, "elements 999 disagrees with sq.obj, which has 800"),
                                   ("flipped", 5000, "flipped 5000 is not a count"),
                                   # a count the map does not have (was shown as "7 of 800")
                                   ("flipped", 7, "flipped 7 disagrees with sq.obj, which has 0 flipped elements"),
                                   ("max_distortion", 0.5, "max_distortion 0.5 disagrees with sq.txt"),
                                   ("measure", "qc", "a qc distortion is at least 1"),
                                   # words no tool writes (taken without a word, exit 0 and 2)
                                   ("task", "banana", 'unknown task "banana"'),
                                   ("status", "weird", 'unknown status "weird"'),
                                   # it ties direct's values in the verdicts
                                   ("delta_k", -1, "delta_k -1 is not a positive number"),
                                   # another map's input (it was filed under the input's section,
                                   # with the warning "input mesh not found")
                                   ("input", "example:bar", "they are not one map's rest and image")):
            edited = dict(summary, **{key: value})
            with open(os.path.join(self.dir, "e.json"), "w") as f:
                json.dump(edited, f)
            p = run("report", "out", "e.json", cwd=self.dir, check_code=1)
            self.assertIn(needle, p.stderr, key)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "out", "index.html")), key)
        # The unedited summary is shown, its figures as written.
        run("report", "out", "sq.json", cwd=self.dir, check_code=0)
        html = read(os.path.join(self.dir, "out", "index.html"))
        self.assertIn("certified lower bound", html)
        # qc's cards show the excess over 1, and say so.
        run("deform", "--example", "square", "--measure", "qc", "--method", "l2", "-o", "q.obj", "--distortion",
            "q.txt", "--summary", "q.json", "--quiet", cwd=self.dir, check_code=0)
        run("report", "outq", "q.json", cwd=self.dir, check_code=0)
        html = read(os.path.join(self.dir, "outq", "index.html"))
        self.assertIn("<td>max distortion \u2212 1</td>", html)
        self.assertIn("<td>L2 of distortion \u2212 1 (area-weighted RMS)</td>", html)

    def test_report_needs_results_it_can_read(self):
        p = run("report", os.path.join(self.dir, "out"), check_code=1)
        self.assertIn("--run", p.stderr)
        with open(os.path.join(self.dir, "x.json"), "w") as f:
            json.dump({"task": "deform", "input": "example:square", "method": "l2"}, f)
        p = run("report", os.path.join(self.dir, "out"), os.path.join(self.dir, "x.json"), check_code=1)
        self.assertIn("no output mesh", p.stderr)
        # A distortion file with NaN or a negative value is not a distortion (it gave a verdict
        # "its maximum is n/a"); a .ply result is not read back (it said "no vertices found").
        run("deform", "--example", "square", "--method", "l2", "-o", "l2.obj", "--distortion", "l2.txt", "--summary",
            "l2.json", "--quiet", cwd=self.dir, check_code=0)
        lines = read(os.path.join(self.dir, "l2.txt")).split("\n")
        for bad in ("nan", "-0.5"):
            with open(os.path.join(self.dir, "l2.txt"), "w") as f:
                f.write("\n".join([bad] + lines[1:]))
            p = run("report", "out2", "l2.json", cwd=self.dir, check_code=1)
            self.assertIn("l2.txt: line 1", p.stderr)
            self.assertIn("not a distortion", p.stderr)
        run("deform", "--example", "square", "--method", "l2", "-o", "l2.ply", "--summary", "ply.json", "--quiet",
            cwd=self.dir, check_code=0)
        # A parametrization's fd cannot be recomputed from its map: the message says to keep the
        # task's distortion file.
        cube = cli_support.write(os.path.join(self.dir, "cube.obj"), "\n".join(cube_obj()[0]) + "\n")
        run("gparam", cube, "-o", "g.obj", "--summary", "g.json", "--quiet", cwd=self.dir, check_code=0)
        p = run("report", "out4", "g.json", cwd=self.dir, check_code=1)
        self.assertIn("run the task with --distortion FILE", p.stderr)
        # Its ARAP can: the OBJ holds the map divided by the edge length h, scaled back by the
        # summary's edge_length (the cube's map is an isometry: 0; without h it was shown as
        # sqrt(2) |1/h - 1| = 4.24 and ranked against the other maps so). The recomputed maximum
        # is checked against the summary's.
        run("gparam", cube, "--measure", "arap", "--method", "linf", "--edge-length", "0.25", "-o", "a.obj",
            "--summary", "a.json", "--quiet", cwd=self.dir, check_code=0)
        run("report", "out6", "a.json", cwd=self.dir, check_code=0)
        html = read(os.path.join(self.dir, "out6", "index.html"))
        self.assertRegex(html, r"max distortion</td><td class=\"v\">[0-9.]+e-1[0-9]<")
        summary = json.loads(read(os.path.join(self.dir, "a.json")))
        summary["edge_length"] = 0.5
        with open(os.path.join(self.dir, "a2.json"), "w") as f:
            json.dump(summary, f)
        p = run("report", "out7", "a2.json", cwd=self.dir, check_code=1)
        self.assertIn("disagrees with a.obj (its distortion recomputed), whose largest value is 1.41421", p.stderr)
        p = run("report", "out3", "ply.json", cwd=self.dir, check_code=1)
        self.assertIn("'.ply' is written by the tasks but not read back", p.stderr)
        # One summary twice, under any name, would be compared with itself.
        with open(os.path.join(self.dir, "l2.txt"), "w") as f:
            f.write("\n".join(lines))
        for twice in (["l2.json", "l2.json"], ["l2.json", "./l2.json"], ["l2.json", os.path.join(self.dir, "l2.json")]):
            p = run("report", "out5", *twice, cwd=self.dir, check_code=1)
            self.assertIn("this summary is given twice", p.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "out5")))
        # A distortion written to stdout ('-') names no file to read: the report says so, as
        # for a run without --distortion.
        p = run("deform", "--example", "square", "--method", "l2", "-o", "d.obj", "--distortion", "-", "--summary",
                "d.json", "--quiet", cwd=self.dir, check_code=0)
        values = [float(x) for x in p.stdout.split()]
        with open(os.path.join(self.dir, "d.json")) as f:
            s = json.load(f)
        self.assertEqual(len(values), s["elements"])
        self.assertAlmostEqual(max(values), s["max_distortion"], places=12)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "-")))
        p = run("report", "out6", "d.json", cwd=self.dir, check_code=0)
        self.assertIn("no distortion_file", p.stderr)
        p = run("deform", "--example", "square", "--distortion", "-", "--summary", "-", cwd=self.dir, check_code=1)
        self.assertIn("both write to stdout", p.stderr)


if __name__ == "__main__":
    unittest.main()
