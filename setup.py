"""The build of campo's Python package for pip (pyproject.toml; docs/python.md, "Install with pip").

setuptools builds nothing itself: its build_ext runs CMake, which configures and builds the
native module campo._campo and libcampo, then installs the component campo_python_package
(python/CMakeLists.txt) into a staging folder: the package in one folder (the pure Python parts,
_campo with an RPATH of $ORIGIN, libcampo under its SONAME beside it, the bundled scenes and
sweep specs in campo/data/scenes), which goes into the wheel as it is.

CAMPO_BUILD_DIR names the CMake build directory: an existing one (tools/setup.sh's build/) is
built as it is configured (up to date, nothing compiles) with the cmake that configured it; a
folder without a CMakeCache.txt is configured there, Release. Unset, the build is build/pip/cmake.
setuptools' own files go to pip/ in that build directory, else to build/pip: nothing in the source tree.
CMAKE_BUILD_PARALLEL_LEVEL sets the parallel jobs (default: all cores).
"""

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = Path(__file__).resolve().parent
COMPONENT = "campo_python_package"
# The CMake build directory named, if any.
NAMED_BUILD_DIR = Path(os.environ["CAMPO_BUILD_DIR"]).resolve() if os.environ.get("CAMPO_BUILD_DIR") else None
# setuptools' own folders (lib..., bdist..., temp..., campo.egg-info): in the named build directory's pip/,
# else build/pip/ (ignored by git; a fresh CMake build goes to its cmake/).
BUILD_BASE = (NAMED_BUILD_DIR or SOURCE_DIR / "build") / "pip"
BUILD_BASE.mkdir(parents=True, exist_ok=True)  # setuptools refuses an egg_base that does not exist yet


def cmake_version():
    """The project's version, from project(campo VERSION x.y.z) in CMakeLists.txt."""
    text = (SOURCE_DIR / "CMakeLists.txt").read_text()
    found = re.search(r"^\s*project\s*\(\s*campo\s+VERSION\s+([0-9][0-9.]*)", text, re.MULTILINE)
    if not found:
        raise RuntimeError("CMakeLists.txt: no project(campo VERSION ...) to take the package's version from")
    return found.group(1)


def cache_entry(build_dir, name):
    """The value of NAME in BUILD_DIR's CMakeCache.txt, or None."""
    for line in (build_dir / "CMakeCache.txt").read_text().splitlines():
        if line.startswith(name + ":"):
            return line.split("=", 1)[1]
    return None


class CMakeBuild(build_ext):
    """Builds and stages the package with CMake instead of compiling the (placeholder) extension."""

    def run(self):
        if self.inplace:
            raise RuntimeError("campo has no editable install: build with tools/setup.sh and use "
                               "PYTHONPATH=build/python (docs/python.md)")
        build_dir, cmake = self.configure()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        self.spawn([cmake, "--build", str(build_dir), "--target", "campo_python", "--parallel", jobs])

        stage = Path(self.build_temp).resolve() / "stage"
        shutil.rmtree(stage, ignore_errors=True)
        self.spawn([cmake, "--install", str(build_dir), "--component", COMPONENT, "--prefix", str(stage)])
        package = stage / "campo"
        self.check_module(package, build_dir)
        target = Path(self.build_lib) / "campo"
        shutil.copytree(package, target, dirs_exist_ok=True)

    def configure(self):
        """The CMake build directory, configured, and the cmake to drive it with."""
        build_dir = NAMED_BUILD_DIR or BUILD_BASE / "cmake"
        if (build_dir / "CMakeCache.txt").is_file():
            # The cmake that configured it: another one (e.g. a pip build environment's) would reconfigure it.
            cmake = cache_entry(build_dir, "CMAKE_COMMAND") or "cmake"
            return build_dir, cmake
        cmake = os.environ.get("CMAKE", "cmake")
        if shutil.which(cmake) is None:
            raise RuntimeError("campo's Python package is built with CMake: install cmake and campo's build "
                               "dependencies (tools/setup.sh)")
        build_dir.mkdir(parents=True, exist_ok=True)
        self.spawn([cmake, "-S", str(SOURCE_DIR), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                    f"-DPython_EXECUTABLE={sys.executable}"])
        return build_dir, cmake

    def check_module(self, package, build_dir):
        """The staged module is for this interpreter (a reused build directory may be configured for another)."""
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        modules = sorted(p.name for p in package.glob("_campo.*"))
        if ["_campo" + suffix] != modules:
            raise RuntimeError(f"{build_dir} built the native module as {modules}, not _campo{suffix} for "
                               f"{sys.executable}: configure it with -DPython_EXECUTABLE={sys.executable}, or "
                               "unset CAMPO_BUILD_DIR to build in a fresh directory")


setup(
    version=cmake_version(),
    package_dir={"": "python"},
    packages=["campo"],
    # The native module, libcampo and campo/data/scenes come from CMake's install of the package (CMakeBuild).
    include_package_data=False,
    # A placeholder: it makes the wheel a platform wheel; CMakeBuild builds the real module.
    ext_modules=[Extension("campo._campo", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(BUILD_BASE)}, "egg_info": {"egg_base": str(BUILD_BASE)}},
)
