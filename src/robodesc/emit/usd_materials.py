"""UsdPreviewSurface materials under ``<robot>/Looks``.

One material prim per distinct (colour, texture): identical materials are shared, and a name never
stands for two looks (Isaac merges materials that share a name). The prim takes the first IR name
seen for that look; a later look with the same name gets a numbered name and keeps the IR name as
its ``displayName``.
"""

from __future__ import annotations

import os

from pxr import Gf, Sdf, UsdShade

from robodesc.emit.usd_context import LOOKS_SCOPE, MATERIALS, UsdContext, unique_name
from robodesc.ir.geometry import RGBA, Material

LookKey = tuple[RGBA | None, str | None]


class MaterialLibrary:
    def __init__(self, ctx: UsdContext) -> None:
        self.ctx = ctx
        self.by_name = {m.name: m for m in ctx.robot.materials}
        self.by_key: dict[LookKey, Sdf.Path] = {}
        self.used: set[str] = set()
        self.scope = ctx.robot_path.AppendChild(LOOKS_SCOPE)

    def resolve(self, material: Material | None) -> Material | None:
        if material is None:
            return None
        if material.is_reference():
            defined = self.by_name.get(material.name)
            if defined is None or defined.is_reference():
                return None
            return defined
        return material

    def path_for(self, material: Material | None) -> Sdf.Path | None:
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

    def _define(self, look: Material, key: LookKey) -> Sdf.Path:
        ctx = self.ctx
        name = unique_name(look.name, self.used, "material")
        with ctx.layer(MATERIALS):
            if len(self.by_key) == 0:
                ctx.stage.DefinePrim(self.scope, "Scope")
            path = self.scope.AppendChild(name)
            material = UsdShade.Material.Define(ctx.stage, path)
            if look.display_name or name != look.name:
                material.GetPrim().SetDisplayName(look.display_name or look.name)
            shader = UsdShade.Shader.Define(ctx.stage, path.AppendChild("PreviewSurface"))
            shader.CreateIdAttr("UsdPreviewSurface")
            color, texture = key
            rgba = color if color is not None else (1.0, 1.0, 1.0, 1.0)
            diffuse = shader.CreateInput("diffuseColor", Sdf.ValueTypeNames.Color3f)
            diffuse.Set(Gf.Vec3f(float(rgba[0]), float(rgba[1]), float(rgba[2])))
            shader.CreateInput("opacity", Sdf.ValueTypeNames.Float).Set(float(rgba[3]))
            shader.CreateInput("roughness", Sdf.ValueTypeNames.Float).Set(0.5)
            surface = shader.CreateOutput("surface", Sdf.ValueTypeNames.Token)
            material.CreateSurfaceOutput().ConnectToSource(surface)
            if texture is not None:
                self._texture(path, diffuse, texture)
        return path

    def _texture(self, path: Sdf.Path, diffuse: UsdShade.Input, texture: str) -> None:
        ctx = self.ctx
        reader = UsdShade.Shader.Define(ctx.stage, path.AppendChild("stReader"))
        reader.CreateIdAttr("UsdPrimvarReader_float2")
        reader.CreateInput("varname", Sdf.ValueTypeNames.Token).Set("st")
        st = reader.CreateOutput("result", Sdf.ValueTypeNames.Float2)
        image = UsdShade.Shader.Define(ctx.stage, path.AppendChild("DiffuseTexture"))
        image.CreateIdAttr("UsdUVTexture")
        asset = texture
        if os.path.isabs(texture):
            asset = os.path.relpath(texture, ctx.layer_dir).replace(os.sep, "/")
            if not asset.startswith("."):
                asset = "./" + asset
        image.CreateInput("file", Sdf.ValueTypeNames.Asset).Set(Sdf.AssetPath(asset))
        image.CreateInput("st", Sdf.ValueTypeNames.Float2).ConnectToSource(st)
        rgb = image.CreateOutput("rgb", Sdf.ValueTypeNames.Float3)
        diffuse.ConnectToSource(rgb)
