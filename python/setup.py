"""Builds the Python package raykernel with the project's CMake (see pyproject.toml for the command).

The extension raykernel._raykernel is the CMake target raykernel_python (python/CMakeLists.txt), built for the
interpreter running this script. The CMake build directory is python/build/cmake, kept between installs so
that a reinstall only rebuilds what changed; RAYKERNEL_CMAKE_BUILD_DIR names another one, e.g. an existing
configured build of the whole project (then only its raykernel_python target is built, its options untouched,
provided it was configured for this same interpreter). RAYKERNEL_BUILD_JOBS sets the build's parallelism.
"""

import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent


def project_version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(raykernel VERSION ([0-9.]+)", text).group(1)


def cache_value(cache: pathlib.Path, name: str) -> str:
    match = re.search(rf"^{name}:[A-Z]+=(.*)$", cache.read_text(), re.M)
    return match.group(1) if match else ""


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        build_dir = pathlib.Path(os.environ.get("RAYKERNEL_CMAKE_BUILD_DIR", HERE / "build" / "cmake")).resolve()
        cache = build_dir / "CMakeCache.txt"
        python = sys.executable
        if cache.exists():
            configured = cache_value(cache, "Python3_EXECUTABLE")
            if os.path.realpath(configured) != os.path.realpath(python):
                sys.exit(f"raykernel: {build_dir} was configured for {configured}, not {python}: "
                         "choose another RAYKERNEL_CMAKE_BUILD_DIR")
            if cache_value(cache, "RAYKERNEL_BUILD_PYTHON") != "ON":
                subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DRAYKERNEL_BUILD_PYTHON=ON"])
        else:
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(
                ["cmake", "-S", str(ROOT), "-B", str(build_dir), *generator, "-DCMAKE_BUILD_TYPE=Release",
                 "-DRAYKERNEL_BUILD_PYTHON=ON", "-DRAYKERNEL_BUILD_TESTS=OFF", "-DRAYKERNEL_BUILD_CLI=ON", "-DRAYKERNEL_WITH_EMBREE=OFF",
                 "-DRAYKERNEL_BUILD_BENCH=OFF", f"-DPython3_EXECUTABLE={python}"])
        jobs = os.environ.get("RAYKERNEL_BUILD_JOBS", str(os.cpu_count() or 1))
        subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "raykernel_python", "-j", jobs])
        built = sorted((build_dir / "python" / "raykernel").glob("_raykernel*" + (self.get_ext_filename("x")[1:])))
        if len(built) != 1:
            sys.exit(f"raykernel: expected one built extension in {build_dir / 'python' / 'raykernel'}, found {built}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], target)


setup(
    version=project_version(),
    packages=["raykernel", "raykernel.testing"],
    package_data={"raykernel": ["py.typed", "*.pyi"]},
    ext_modules=[CMakeExtension("raykernel._raykernel")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
