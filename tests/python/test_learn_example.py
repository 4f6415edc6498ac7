"""examples/python/learn_forest_flight.py in its quick mode: it runs and writes what it says it writes.

A smoke test of the example (two generations of four candidates, a short video), not of how well it
learns: that is measured by running it in full (examples/python/README.md). Gymnasium comes from the
environment, else from CAMPO_GYMNASIUM_PATH; without either the test is skipped with the reason,
unless CAMPO_REQUIRE_GYMNASIUM=1, where that is a failure (as in test_gym.py).
"""

import json
import os
import pathlib
import subprocess
import sys
import tempfile
import unittest

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "learn_forest_flight.py"

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from gymnasium_support import needs_gymnasium  # noqa: E402 (this folder, just above)


@needs_gymnasium
class LearnExampleQuick(unittest.TestCase):
    def run_quick(self, out: pathlib.Path) -> subprocess.CompletedProcess:
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(p for p in sys.path if p)
        return subprocess.run([sys.executable, str(EXAMPLE), "--quick", "--seed", "3", "--out", str(out)],
                              env=env, capture_output=True, text=True, timeout=300)

    def test_quick_run_writes_its_outputs(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = pathlib.Path(tmp) / "learn"
            done = self.run_quick(out)
            self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            # Progress is printed per generation.
            self.assertIn("generation   1:", done.stdout)
            self.assertIn("generation   2:", done.stdout)
            for name in ("learning_curve.png", "flight.mp4", "policy.npz", "summary.json"):
                self.assertGreater((out / name).stat().st_size, 0, name)
            self.assertEqual((out / "learning_curve.png").read_bytes()[:8], b"\x89PNG\r\n\x1a\n")
            # An MP4 names its box type "ftyp" in bytes 4-8.
            self.assertEqual((out / "flight.mp4").read_bytes()[4:8], b"ftyp")

            summary = json.loads((out / "summary.json").read_text())
            self.assertEqual(summary["generations"], 2)
            self.assertEqual(summary["population"], 4)
            self.assertTrue(summary["quick"])
            self.assertEqual(len(summary["history"]), 2)
            # Each generation flies every candidate and the distribution mean in every training forest.
            self.assertEqual(summary["evaluations"], 2 * (4 + 1) * summary["forests_per_generation"])
            self.assertGreater(summary["wall_time_s"], 0.0)
            held_out = summary["held_out"]
            for key in ("success_fraction", "baseline_success_fraction"):
                self.assertGreaterEqual(held_out[key], 0.0)
                self.assertLessEqual(held_out[key], 1.0)
            # The evaluation's forests are not among those trained on.
            trained = {f for h in summary["history"] for f in h["forests"]}
            first, last = held_out["forest_seeds"]
            self.assertFalse(any(first <= f <= last for f in trained))
            self.assertEqual(last - first + 1, held_out["episodes"])

            import numpy as np

            policy = np.load(out / "policy.npz")
            self.assertEqual(policy["theta"].size, summary["policy_parameters"])

    def test_same_seed_same_run(self):
        # Deterministic for a given --seed: the learning history and the policy repeat exactly.
        with tempfile.TemporaryDirectory() as tmp:
            a, b = pathlib.Path(tmp) / "a", pathlib.Path(tmp) / "b"
            for out in (a, b):
                done = self.run_quick(out)
                self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
            sa, sb = (json.loads((o / "summary.json").read_text()) for o in (a, b))
            strip = lambda h: [{k: v for k, v in g.items() if k != "elapsed_s"} for g in h]  # noqa: E731
            self.assertEqual(strip(sa["history"]), strip(sb["history"]))
            self.assertEqual(sa["held_out"], sb["held_out"])
            import numpy as np

            self.assertTrue(np.array_equal(np.load(a / "policy.npz")["theta"], np.load(b / "policy.npz")["theta"]))


if __name__ == "__main__":
    unittest.main()
