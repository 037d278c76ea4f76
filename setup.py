"""Builds robodesc's C extensions; everything else is in pyproject.toml.

- ``robodesc.meshes._numtext`` parses the numbers in mesh text (COLLADA, OBJ) about seven times faster
  than numpy;
- ``robodesc.meshes._weld`` welds mesh corners into points and computes face normals about five times
  faster than robodesc's numpy code;
- ``robodesc.usdfile._intcode`` writes the integer coding of .usdc int arrays (mesh indices), which
  Python would take seconds over.

All are optional: without a C compiler the install goes on and robodesc uses its numpy code
instead, which gives the same numbers bit for bit, more slowly. FMA contraction is off so the
normals are computed with exactly numpy's roundings.
"""

import sys

from setuptools import Extension, setup

# MSVC neither contracts to FMA by default nor knows the GCC/Clang flag.
STRICT_FP = [] if sys.platform == "win32" else ["-ffp-contract=off"]

setup(
    ext_modules=[
        Extension("robodesc.meshes._numtext", sources=["src/robodesc/meshes/_numtext.c"], optional=True),
        Extension(
            "robodesc.meshes._weld",
            sources=["src/robodesc/meshes/_weld.c"],
            extra_compile_args=STRICT_FP,
            optional=True,
        ),
        Extension("robodesc.usdfile._intcode", sources=["src/robodesc/usdfile/_intcode.c"], optional=True),
    ]
)
