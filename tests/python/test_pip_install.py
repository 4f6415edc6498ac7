"""`pip install .` into a fresh virtual environment, then campo from far away (pyproject.toml, setup.py;
docs/python.md, "Install with pip").

A temporary venv of Debian's /usr/bin/python3 (--system-site-packages: its setuptools, wheel, numpy
and pandas) gets `pip install --no-build-isolation --no-deps --no-index SOURCE`, offline, with
CAMPO_BUILD_DIR naming this CTest build directory, so the package is staged from the objects already
built (no second build). Then the venv's python, in another temporary folder with no PYTHONPATH,
imports campo from the venv, runs a bundled scene by name and finds a bundled sweep spec, all from
inside the installed package: nothing from the source or build tree. The source tree gains no file
git would show. Run by CTest with CAMPO_SOURCE_DIR and CAMPO_BUILD_DIR (tests/CMakeLists.txt).
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
from pathlib import Path

SOURCE_DIR = Path(os.environ.get("CAMPO_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BUILD_DIR = Path(os.environ.get("CAMPO_BUILD_DIR", SOURCE_DIR / "build")).resolve()
PYTHON = sys.executable  # the interpreter the module is built for (CTest: Python_EXECUTABLE, Debian's)
SCENE = "two_drones_head_on"
SPEC = "resolution_000"
UNKNOWN = "no_such_bundled_scene"

# What the installed package reports, run from a folder far from the source tree.
PROBE = r"""
import json, pathlib, sys
import campo
import importlib.metadata
report = {"package": campo.__file__, "module": campo._campo.__file__, "version": campo.__version__,
          "distribution_version": importlib.metadata.version("campo"), "scene": str(campo.bundled_scene(sys.argv[1]))}
result = campo.run(sys.argv[1])
report["vehicles"] = sorted(vehicle["alias"] for vehicle in result["vehicles"])
# A short episode of a bundled scene named as Episode takes it.
episode = campo.Episode("two_barriers", seed=1)
obs = episode.reset()
for _ in range(5):
    obs, done, info = episode.step(campo.Command.go_to(obs.mission_m[-1], speed_mps=0.6))
report["episode_time_s"] = info["time_s"]
spec = pathlib.Path(campo.__file__).parent / "data" / "scenes" / "sweeps" / (sys.argv[2] + ".json")
report["spec"] = str(spec)
report["spec_scenes"] = {name: str(campo.bundled_scene(name)) for name in json.loads(spec.read_text())["scenes"]}
try:
    campo.bundled_scene(sys.argv[3])
    report["unknown"] = None
except campo.InputError as e:
    report["unknown"] = str(e)
report["libraries"] = sorted({line.split()[-1] for line in open("/proc/self/maps") if "libcampo." in line})
print(json.dumps(report))
"""


def clean_environment():
    """The caller's environment without what would point Python, pip or campo elsewhere."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "PIP_", "LD_", "CAMPO_", "VIRTUAL_ENV"))}


# What setuptools and pip could leave in a source tree: metadata, eggs, wheels, a built module in place.
SETUPTOOLS_LEFTOVERS = re.compile(r"(\.egg-info/|^\.eggs/|^dist/|^build/|\.whl$|^python/campo/[^/]*\.so$)")


def untracked(folder):
    """The files git shows as untracked in folder that setuptools could have written; None outside a checkout.
    (Only those: other work in a shared checkout may add files while the test runs.)"""
    if shutil.which("git") is None:
        return None
    done = subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=folder,
                          capture_output=True, text=True)
    if done.returncode != 0:
        return None
    files = {line[3:] for line in done.stdout.splitlines() if line.startswith("??")}
    return {f for f in files if SETUPTOOLS_LEFTOVERS.search(f)}


def under(path, folder):
    return Path(path).resolve().is_relative_to(Path(folder).resolve())


class PipInstall(unittest.TestCase):
    def test_pip_installs_a_package_that_runs_from_anywhere(self):
        with tempfile.TemporaryDirectory(prefix="campo_pip_") as work:
            work = Path(work)
            venv = work / "venv"
            made = subprocess.run([PYTHON, "-m", "venv", "--system-site-packages", str(venv)], capture_output=True,
                                  text=True, timeout=300)
            self.assertEqual(made.returncode, 0, f"python3 -m venv (Debian: python3-venv):\n{made.stderr}")

            before = untracked(SOURCE_DIR)
            env = clean_environment()
            env["CAMPO_BUILD_DIR"] = str(BUILD_DIR)
            env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
            start = time.monotonic()
            installed = subprocess.run([str(venv / "bin" / "pip"), "install", "--verbose", "--no-build-isolation",
                                        "--no-deps", "--no-index", "--no-cache-dir", str(SOURCE_DIR)],
                                       cwd=work, env=env, capture_output=True, text=True, timeout=3000)
            seconds = time.monotonic() - start
            self.assertEqual(installed.returncode, 0, f"pip install failed:\n{installed.stdout}\n{installed.stderr}")
            print(f"pip install with CAMPO_BUILD_DIR={BUILD_DIR}: {seconds:.1f} s")
            # The package came from this build directory's objects, not from a build of its own.
            log = installed.stdout + installed.stderr  # pip -v: the backend's output, on stderr
            self.assertIn(f"--build {BUILD_DIR} --target campo_python", log)
            self.assertIn(f"--install {BUILD_DIR} --component campo_python_package", log)
            if before is not None:
                self.assertEqual(untracked(SOURCE_DIR) - before, set(), "pip left files in the source tree")

            elsewhere = work / "elsewhere"
            elsewhere.mkdir()
            probed = subprocess.run([str(venv / "bin" / "python"), "-c", PROBE, SCENE, SPEC, UNKNOWN], cwd=elsewhere,
                                    env=clean_environment(), capture_output=True, text=True, timeout=600)
            self.assertEqual(probed.returncode, 0, f"the installed campo failed:\n{probed.stderr}")
            report = json.loads(probed.stdout.strip().splitlines()[-1])

        site = venv / "lib"
        # Everything from inside the venv: the package, its module, libcampo, the scenes and the spec.
        for key in ("package", "module", "scene", "spec"):
            self.assertTrue(under(report[key], site), f"{key} from outside the venv: {report[key]}")
        data = Path(report["package"]).parent / "data" / "scenes"
        self.assertEqual(Path(report["scene"]), data / f"{SCENE}.json")
        self.assertEqual(Path(report["spec"]), data / "sweeps" / f"{SPEC}.json")
        self.assertTrue(report["spec_scenes"])
        for name, scene in report["spec_scenes"].items():
            self.assertEqual(Path(scene), data / f"{name}.json")
        self.assertTrue(report["libraries"], "libcampo is not loaded")
        for library in report["libraries"]:
            self.assertTrue(under(library, site), f"libcampo loaded from outside the venv: {library}")
        # The distribution's version (pyproject.toml's, from CMakeLists.txt) is the native module's.
        self.assertEqual(report["distribution_version"], report["version"])

        # The bundled scene ran its vehicles (the scene file's quadrotors and rovers), and the episode stepped.
        objects = json.loads((SOURCE_DIR / "scenes" / f"{SCENE}.json").read_text())["objects"]
        vehicles = sorted(o["alias"] for o in objects if o["type"] in ("quadrotor", "rover"))
        self.assertEqual(report["vehicles"], vehicles)
        self.assertGreater(report["episode_time_s"], 0.0)

        # An unknown name lists the working folder's scenes/ and the package's, nothing of the trees.
        message = report["unknown"]
        self.assertIsNotNone(message)
        self.assertIn(f"looked for {UNKNOWN}.json in scenes (from the working directory), {data}", message)
        self.assertNotIn(str(SOURCE_DIR), message)
        self.assertNotIn(str(BUILD_DIR), message)


if __name__ == "__main__":
    unittest.main()
