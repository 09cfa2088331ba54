"""The wheel's build step: the extension repose._repose is built by the project's CMake (Release, without
tests, tools or benchmarks) and copied into the wheel next to the pure-Python package. Offline:
    pip wheel --no-build-isolation --no-deps python/ -w dist/
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent.parent


class CMakeExtension(build_ext):
    def build_extension(self, ext):
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        subprocess.check_call([
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DREPOSE_PYTHON=ON",
            "-DREPOSE_BUILD_TESTS=OFF", "-DREPOSE_BUILD_APPS=OFF", "-DREPOSE_BUILD_BENCH=OFF", "-DREPOSE_MPI=OFF",
            f"-DPython3_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_repose", "-j", str(os.cpu_count() or 1)])
        built = next((build / "python" / "repose").glob("_repose*" + (".pyd" if os.name == "nt" else ".so")))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(ext_modules=[Extension("repose._repose", sources=[])], cmdclass={"build_ext": CMakeExtension})
