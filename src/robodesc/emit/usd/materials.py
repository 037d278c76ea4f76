"""UsdPreviewSurface materials under ``<robot>/Looks``.

One material prim per distinct (colour, texture): identical materials are shared, and a name never
stands for two looks (Isaac merges materials that share a name). The prim takes the first IR name
seen for that look; a later look with the same name gets a numbered name and keeps the IR name as
its ``displayName``.
"""

from __future__ import annotations

import os

from robodesc.emit.usd.context import LOOKS_SCOPE, MATERIALS, UsdContext, unique_name
from robodesc.ir.geometry import RGBA, Material
from robodesc.usdfile.spec import AssetPath

LookKey = tuple[RGBA | None, str | None]


class MaterialLibrary:
    def __init__(self, ctx: UsdContext) -> None:
        self.ctx = ctx
        self.by_name = {m.name: m for m in ctx.robot.materials}
        self.by_key: dict[LookKey, str] = {}
        self.used: set[str] = set()
        self.scope = f"{ctx.robot_path}/{LOOKS_SCOPE}"

    def resolve(self, material: Material | None) -> Material | None:
        if material is None:
            return None
        if material.is_reference():
            defined = self.by_name.get(material.name)
            if defined is None or defined.is_reference():
                return None
            return defined
        return material

    def path_for(self, material: Material | None) -> str | None:
        look = self.resolve(material)
        if look is None:
            return None
        texture = look.texture_path or look.texture
        key: LookKey = (look.color, texture)
        path = self.by_key.get(key)
        if path is None:
            path = self._define(look, key)
            self.by_key[key] = path
        return path

    def _define(self, look: Material, key: LookKey) -> str:
        ctx = self.ctx
        name = unique_name(look.name, self.used, "material")
        if len(self.by_key) == 0:
            ctx.define(MATERIALS, self.scope, "Scope")
        path = f"{self.scope}/{name}"
        material = ctx.define(MATERIALS, path, "Material")
        if look.display_name or name != look.name:
            material.display_name = look.display_name or look.name
        shader = ctx.define(MATERIALS, f"{path}/PreviewSurface", "Shader")
        shader.attr("info:id", "token", "UsdPreviewSurface", uniform=True)
        color, texture = key
        rgba = color if color is not None else (1.0, 1.0, 1.0, 1.0)
        diffuse = shader.attr("inputs:diffuseColor", "color3f", (float(rgba[0]), float(rgba[1]), float(rgba[2])))
        shader.attr("inputs:opacity", "float", float(rgba[3]))
        shader.attr("inputs:roughness", "float", 0.5)
        shader.attr("outputs:surface", "token", None)
        material.connect("outputs:surface", "token", f"{path}/PreviewSurface.outputs:surface")
        if texture is not None:
            diffuse.connections = [self._texture(path, texture)]
        return path

    def _texture(self, path: str, texture: str) -> str:
        """The texture reader shaders; returns the output the diffuse colour connects to."""
        ctx = self.ctx
        reader = ctx.define(MATERIALS, f"{path}/stReader", "Shader")
        reader.attr("info:id", "token", "UsdPrimvarReader_float2", uniform=True)
        reader.attr("inputs:varname", "token", "st")
        reader.attr("outputs:result", "float2", None)
        image = ctx.define(MATERIALS, f"{path}/DiffuseTexture", "Shader")
        image.attr("info:id", "token", "UsdUVTexture", uniform=True)
        asset = texture
        if os.path.isabs(texture):
            asset = os.path.relpath(texture, ctx.layer_dir).replace(os.sep, "/")
            if not asset.startswith("."):
                asset = "./" + asset
        image.attr("inputs:file", "asset", AssetPath(asset))
        image.connect("inputs:st", "float2", f"{path}/stReader.outputs:result")
        image.attr("outputs:rgb", "float3", None)
        return f"{path}/DiffuseTexture.outputs:rgb"
