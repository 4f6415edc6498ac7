"""Python finds the bundled scenes as `campo run` does, from any working folder:
in the build tree and in an installed prefix (sweep/bundled.cpp, docs/python.md).

Each check runs a fresh /usr/bin/python3 in a new temporary folder (no scenes/
there) with PYTHONPATH naming only the module under test. Run by CTest with
CAMPO_SOURCE_DIR, CAMPO_BUILD_DIR and CAMPO_CMAKE (tests/CMakeLists.txt):
    test_bundled.py BuildTree   the module of build/python
    test_bundled.py Installed   cmake --install to a temporary prefix, its module
"""

import glob
import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SOURCE_DIR = Path(os.environ.get("CAMPO_SOURCE_DIR", Path(__file__).resolve().parents[2])).resolve()
BUILD_DIR = Path(os.environ.get("CAMPO_BUILD_DIR", SOURCE_DIR / "build")).resolve()
CMAKE = os.environ.get("CAMPO_CMAKE", "cmake")
PYTHON = "/usr/bin/python3"
UNKNOWN = "no_such_bundled_scene"

# What the child reports: the scene campo.Episode loaded (it loads at construction), where the
# module and libcampo came from, and the error for a name no folder holds.
PROBE = r"""
import json, sys
import campo
episode = campo.Episode("two_barriers", seed=1)
episode.reset()
try:
    campo.Episode(sys.argv[1])
    unknown = None
except campo.InputError as e:
    unknown = str(e)
libraries = sorted({line.split()[-1] for line in open("/proc/self/maps") if "libcampo." in line})
print(json.dumps({"scene": str(campo.bundled_scene("two_barriers")), "module": campo._campo.__file__,
                  "libraries": libraries, "unknown": unknown}))
"""


def probe(pythonpath, folder):
    """PROBE's report from a child in `folder` whose only extra import path is `pythonpath`."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "LD_", "CAMPO_"))}
    env["PYTHONPATH"] = str(pythonpath)
    done = subprocess.run([PYTHON, "-c", PROBE, UNKNOWN], cwd=folder, env=env, capture_output=True, text=True,
                          timeout=120)
    if done.returncode != 0:
        raise AssertionError(f"python3 in {folder} failed ({done.returncode}):\n{done.stderr}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def under(path, folder):
    return Path(path).resolve().is_relative_to(Path(folder).resolve())


class BuildTree(unittest.TestCase):
    def test_a_temporary_folder_finds_the_source_trees_scenes(self):
        with tempfile.TemporaryDirectory(prefix="campo_bundled_") as folder:
            report = probe(BUILD_DIR / "python", folder)
        self.assertTrue(under(report["module"], BUILD_DIR / "python"), report["module"])
        self.assertEqual(Path(report["scene"]), SOURCE_DIR / "scenes" / "two_barriers.json")
        # The unknown name: where it was looked for, the working folder's scenes/ first.
        message = report["unknown"]
        self.assertIsNotNone(message)
        self.assertIn(f"{UNKNOWN}: no bundled scene of that name: looked for {UNKNOWN}.json in scenes "
                      "(from the working directory), ", message)
        self.assertIn(str(SOURCE_DIR / "scenes"), message)


class Installed(unittest.TestCase):
    def test_an_installed_prefix_finds_its_own_scenes(self):
        with tempfile.TemporaryDirectory(prefix="campo_installed_python_") as work:
            prefix = Path(work) / "prefix"
            installed = subprocess.run([CMAKE, "--install", str(BUILD_DIR), "--prefix", str(prefix)],
                                       capture_output=True, text=True, timeout=300)
            self.assertEqual(installed.returncode, 0, installed.stderr)
            packages = glob.glob(str(prefix / "**" / "campo" / "__init__.py"), recursive=True)
            self.assertEqual(len(packages), 1, f"the Python package installed once under {prefix}: {packages}")
            pythonpath = Path(packages[0]).parent.parent
            folder = Path(work) / "elsewhere"
            folder.mkdir()
            report = probe(pythonpath, folder)

            # Everything from the prefix: the module, libcampo, the scene.
            self.assertTrue(under(report["module"], prefix), report["module"])
            self.assertTrue(report["libraries"], "libcampo is not loaded")
            for library in report["libraries"]:
                self.assertTrue(under(library, prefix), f"libcampo loaded from outside the prefix: {library}")
            self.assertEqual(Path(report["scene"]), prefix / "share" / "campo" / "scenes" / "two_barriers.json")
            message = report["unknown"]
            self.assertIn(str(prefix / "share" / "campo" / "scenes"), message)
            self.assertNotIn(str(SOURCE_DIR), message)
            self.assertNotIn(str(BUILD_DIR), message)

            # The installed program looks in the same places and says so in the same words.
            cli = subprocess.run([str(prefix / "bin" / "campo"), "run", UNKNOWN, "--out", "run"], cwd=folder,
                                 capture_output=True, text=True, timeout=60)
            self.assertNotEqual(cli.returncode, 0)
            self.assertIn(message, cli.stderr)


if __name__ == "__main__":
    unittest.main()
