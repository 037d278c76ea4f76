"""IR → IR rewrites: one module per pass, run in the order of :data:`robodesc.passes.pipeline.PASSES`."""

from robodesc.passes.context import PassContext
from robodesc.passes.options import PassOptions
from robodesc.passes.pipeline import PASSES, run_passes
from robodesc.passes.presets import PRESET_OPTIONS, PRESETS, preset_options

__all__ = ["PASSES", "PRESETS", "PRESET_OPTIONS", "PassContext", "PassOptions", "preset_options", "run_passes"]
