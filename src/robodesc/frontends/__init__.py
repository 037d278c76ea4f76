"""Frontends: URDF, xacro and compositions → IR."""
