"""The named camera directions, apart from the camera maths so the CLI can list them without numpy."""

from __future__ import annotations

# azimuth, elevation in degrees (MuJoCo's free camera: azimuth 0 looks along +x, elevation < 0
# looks down). URDF robots face +x: "front" stands in front of the robot looking back at it.
VIEWS: dict[str, tuple[float, float]] = {
    "front": (180.0, -8.0),
    "side": (90.0, -8.0),
    "top": (180.0, -89.0),
    "iso": (140.0, -28.0),
}
