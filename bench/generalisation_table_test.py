#!/usr/bin/env python3
"""Tests of bench/generalisation_table.py on a made-up OUT_DIR: the cells, the
verdict columns (COLMAP's included) and the medians.

usage: generalisation_table_test.py   (exit 0: passed)
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "generalisation_table.py")


def overall(rot, fov=0.0, zoom=0.0, ate=0.1, lost_share=0.0, unmatched_gt=0):
    return {"frames": {"gt": 100, "matched": 100 - unmatched_gt, "unmatched_gt": unmatched_gt},
            "overall": {"rotation_deg": {"mean": rot}, "fov_percent": {"mean": fov},
                        "zoom_ratio_percent": {"mean": zoom}, "ate_percent": ate,
                        "gt_static": False, "spurious_translation": None,
                        "model_agreement": 1.0, "lost_share": lost_share}}


class GeneralisationTableTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = self.tmp.name
        os.makedirs(os.path.join(self.out, "runs", "presets"))
        os.makedirs(os.path.join(self.out, "decode", "presets"))

    def tearDown(self):
        self.tmp.cleanup()

    def run_(self, clip, method, seconds, rc, report=None, err=""):
        base = os.path.join(self.out, "runs", "presets", "%s.%s" % (clip, method))
        with open(base + ".time", "w") as f:
            f.write("%s %d\n" % (seconds, rc))
        with open(base + ".err", "w") as f:
            f.write(err)
        if report is not None:
            with open(base + ".json", "w") as f:
                json.dump(report, f)

    def table(self, label="4 images/s, 480 px"):
        with open(os.path.join(self.out, "decode", "presets", "traveling.time"), "w") as f:
            f.write("2.0\n")
        res = subprocess.run([sys.executable, SCRIPT, self.out, "abc1234", "1", label],
                             capture_output=True, text=True, check=True)
        return res.stdout

    def row(self, text, clip):
        return next(l for l in text.splitlines() if "| %s |" % clip in l)

    def test_colmap_cell_says_what_it_registered_and_its_verdict(self):
        self.run_("traveling", "default", 4.0, 0, overall(0.04))
        self.run_("traveling", "draft", 2.0, 0, overall(0.2, lost_share=0.05))
        self.run_("traveling", "colmap", 40.0, 0, overall(0.02, unmatched_gt=20),
                  "colmap: 33 of 34 images registered (1 frame in 5, 480 px)\n")
        text = self.table()
        cells = [c.strip() for c in self.row(text, "traveling").split("|")[1:-1]]
        self.assertIn("(33 of 34 images)", cells[8])
        self.assertIn("lost 20 %", cells[8])  # frames without a row count as not placed
        self.assertEqual(cells[9], "40.0 (20.0x)")
        self.assertIn("lost 5 %", cells[6])
        self.assertEqual(cells[-3:], ["PASS", "FAIL", "PASS"])  # default, draft, colmap
        self.assertIn("COLMAP: 4 images/s, 480 px", text)

    def test_a_colmap_run_past_its_limit_is_a_failure(self):
        self.run_("traveling", "default", 4.0, 0, overall(0.04))
        self.run_("traveling", "draft", 2.0, 0, overall(0.04))
        self.run_("traveling", "colmap", 300.0, 124, None, "time limit 300 s\n")
        cells = [c.strip() for c in self.row(self.table(), "traveling").split("|")[1:-1]]
        self.assertEqual(cells[8], "failed: time limit 300 s")
        self.assertEqual(cells[-1], "FAIL")

    def test_the_header_has_one_verdict_column_per_method(self):
        self.run_("traveling", "default", 4.0, 0, overall(0.04))
        text = self.table()
        head = next(l for l in text.splitlines() if l.startswith("| split |"))
        self.assertEqual(head.count("vs target"), 3)
        rule = text.splitlines()[text.splitlines().index(head) + 1]
        self.assertEqual(rule.count("---"), head.count("|") - 1)
        # Runs not made say so and judge nothing.
        cells = [c.strip() for c in self.row(text, "traveling").split("|")[1:-1]]
        self.assertEqual(cells[6], "not run")
        self.assertEqual(cells[-1], "-")


if __name__ == "__main__":
    unittest.main()
