"""The compiled summary path (dissector/accel/_summary.c); everything else is declared in pyproject.toml.

The extension is optional: without a C compiler the package installs and runs on the pure-Python
stages, which are the reference the extension is tested against (tests/test_fastsummary.py).
"""
from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "dissector.accel._summary",
            ["dissector/accel/_summary.c"],
            extra_compile_args=["-O2", "-std=c99", "-Wall", "-Wextra", "-Wno-unused-parameter", "-Wno-missing-field-initializers", "-Wno-cast-function-type"],
            optional=True,
        )
    ]
)
