"""Smoke test of vector_env_throughput.py --quick (CTest python/vector_env_throughput_quick): the script runs,
prints its table and writes its JSON with provenance, every case and variant measured with a rate > 0, and
the three variants did the same simulated work. No timing targets: rates depend on the machine and its load.

Gymnasium as gymnasium_support finds it: installed, else CAMPO_GYMNASIUM_PATH; without either the test is
skipped with the reason, unless CAMPO_REQUIRE_GYMNASIUM=1 (.ci/run), where that is a failure."""
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import unittest

SCRIPT = pathlib.Path(__file__).resolve().parents[2] / "bench" / "python" / "vector_env_throughput.py"

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from gymnasium_support import needs_gymnasium  # noqa: E402 (this folder, just above)


@needs_gymnasium
class QuickRun(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        out = pathlib.Path(cls.folder.name) / "throughput.json"
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
        cls.process = subprocess.run([sys.executable, str(SCRIPT), "--quick", "--json", str(out)], capture_output=True,
                                     text=True, timeout=300, env=env)
        if cls.process.returncode != 0:
            raise AssertionError(f"exit {cls.process.returncode}\n{cls.process.stdout}\n{cls.process.stderr}")
        cls.report = json.loads(out.read_text())

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_provenance(self):
        p = self.report["provenance"]
        self.assertGreaterEqual(p["machine"]["nproc"], 1)
        self.assertTrue(p["machine"]["cpu_model"])
        self.assertIn("--quick", p["command"])
        self.assertTrue(p["date_utc"])
        self.assertIn("revision", p["git"])

    def test_every_case_and_variant_has_positive_rates(self):
        config = self.report["config"]
        self.assertEqual(config["scene"], "trees_rolling_terrain")
        self.assertEqual(config["action_mode"], "velocity")
        results = self.report["results"]
        cases = {(r["resolution"], r["num_envs"], r["variant"]) for r in results}
        expected = {(res, n, v) for res in config["resolutions"] for n in config["num_envs"]
                    for v in ("vector", "vector_1", "loop")}
        self.assertEqual(cases, expected)
        self.assertEqual(len(results), len(expected))
        for r in results:
            self.assertEqual(len(r["rates_env_steps_per_s"]), config["repeats"])
            self.assertTrue(all(rate > 0 for rate in r["rates_env_steps_per_s"]), r)
            self.assertLessEqual(r["min"], r["median"])
            self.assertLessEqual(r["median"], r["max"])
            self.assertEqual(r["env_steps_per_repeat"], r["vector_steps_per_repeat"] * r["num_envs"])
        threads = {r["variant"]: r["num_threads"] for r in results}
        self.assertEqual(threads["vector_1"], 1)
        self.assertEqual(threads["vector"], config["threads"])

    def test_the_variants_did_the_same_work(self):
        # Same seeds and actions, environments that share nothing: each one's rewards and episode ends agree.
        self.assertTrue(all(r["same_work_as_vector_1"] for r in self.report["results"]))

    def test_ratios_and_table(self):
        config = self.report["config"]
        self.assertEqual(len(self.report["ratios"]), len(config["resolutions"]) * len(config["num_envs"]))
        for q in self.report["ratios"]:
            self.assertGreater(q["threads_over_1_thread"], 0)
            self.assertGreater(q["vector_over_loop"], 0)
        self.assertIn("| LIDAR | N |", self.process.stdout)
        self.assertEqual(self.report["markdown"].count("\n| 16 x 16 |"), len(config["num_envs"]))
        for seconds in self.report["reset_s_median"].values():
            self.assertGreater(seconds, 0)


if __name__ == "__main__":
    unittest.main()
