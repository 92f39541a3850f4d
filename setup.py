"""`python3 -m pip install --no-build-isolation .`: builds the Python module with the
project's CMake (Debian's setuptools and wheel only; nothing is downloaded) and installs the
`strictmin` package. Extra CMake arguments: the CMAKE_ARGS environment variable."""
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     "-DSTRICTMIN_BUILD_TESTS=OFF", "-DSTRICTMIN_BUILD_BENCH=OFF", "-DSTRICTMIN_BUILD_PYTHON=ON",
                     f"-DPython3_EXECUTABLE={sys.executable}", *shlex.split(os.environ.get("CMAKE_ARGS", ""))]
        subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_strictmin", "-j", str(os.cpu_count() or 1)])
        built = next((build / "python" / "strictmin").glob("_strictmin*.so"))
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    name="strictmin",
    version="0.1.0",
    description="Maps of meshes with the least possible worst-case distortion (Levi & Zorin 2014)",
    packages=["strictmin"],
    package_dir={"strictmin": "python/strictmin"},
    ext_modules=[Extension("strictmin._strictmin", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    install_requires=["numpy"],
    python_requires=">=3.9",
    zip_safe=False,
)
