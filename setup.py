"""Builds robodesc's one C extension; everything else is in pyproject.toml.

``robodesc._numtext`` parses the numbers in mesh files about five times faster than numpy. It is
optional: without a C compiler the install goes on and robodesc parses with numpy instead (same
numbers, slower).
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "robodesc._numtext",
            sources=["src/robodesc/_numtext.c"],
            optional=True,
        )
    ]
)
