"""Builds the extension module _imunoise with CMake (the library, pybind11 and the optional
HDF5 reader module) and puts it, with the HDF5 module, inside the package directory."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build_dir = Path(os.environ.get("IMUNOISE_BUILD_DIR") or Path(self.build_temp).resolve() / "cmake")
        if not (build_dir / "CMakeCache.txt").exists():
            subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                            "-DIMUNOISE_BUILD_TESTS=OFF", "-DIMUNOISE_BUILD_BENCH=OFF",
                            "-DIMUNOISE_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"], check=True)
        targets = ["_imunoise"]
        if subprocess.run(["cmake", "--build", str(build_dir), "--target", "help"], check=True,
                          capture_output=True, text=True).stdout.find("imunoise_hdf5") >= 0:
            targets.append("imunoise_hdf5")
        subprocess.run(["cmake", "--build", str(build_dir), "-j", str(os.cpu_count() or 1), "--target", *targets],
                       check=True)
        built = next((build_dir / "python" / "imunoise").glob("_imunoise*.so"))
        destination = Path(self.get_ext_fullpath(ext.name))
        destination.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, destination)
        # The HDF5 reader is a module the library loads on the first HDF5 file, looked for
        # beside the extension first.
        for module in build_dir.glob("apps/imunoise/libimunoise_hdf5.so"):
            shutil.copy2(module, destination.parent / module.name)


setup(
    packages=["imunoise"],
    package_dir={"imunoise": "python/imunoise"},
    ext_modules=[CMakeExtension("imunoise._imunoise")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
