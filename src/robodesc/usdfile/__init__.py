"""USD layers without usd-core: an in-memory layer model (:mod:`.spec`) and its ``.usda``
(:mod:`.usda`) and ``.usdc`` crate (:mod:`.usdc`) writers. :mod:`robodesc.emit.usd` builds on it.

Why it exists: speed. Importing usd-core's ``pxr`` costs about 0.2 s, as much as converting a small
robot, and writing through ``Sdf`` is slower still: on a 400k-point, 2.3M-index mesh layer,
``usdc_bytes`` plus the write takes 0.06 s against 0.41 s for ``Sdf`` + ``Export``
(``benchmarks/usdc_write_speed.py``, this 2-core machine). Without it the USD target could not be
three times faster than NVIDIA's converter (docs/usd.md, Speed).

What guards it, since it re-implements file formats:
- ``tests/usdfile``: the ``.usda`` text is byte-identical to ``Sdf.Layer.ExportToString`` for the
  same specs, and every value type written to ``.usdc`` reads back through usd-core unchanged;
- ``tests/usd``: every corpus robot's USD is read back through usd-core's physics parser and
  compared with the IR (bodies, joints, limits, drives, masses, forward kinematics);
- the golden ``.usda`` files were written by usd-core and are reproduced byte for byte.

It imports nothing else of robodesc.
"""
