"""Isaac Sim target: one folder with the USD asset, the Isaac-flavoured URDF, importer settings,
an Isaac Lab ``ArticulationCfg`` module and the reports. Entry point: :func:`write_isaac_folder`."""

from robodesc.emit.isaac.folder import findings_markdown, write_isaac_folder
from robodesc.emit.isaac.settings import IsaacSettings
from robodesc.emit.isaac.target import TARGET

__all__ = ["TARGET", "IsaacSettings", "findings_markdown", "write_isaac_folder"]
