"""Mesh files → arrays: STL, OBJ and COLLADA readers, the weld and face normals, the number parser
and the two C extensions that make them fast (``_numtext``, ``_weld``), with trimesh for any other
format.

The USD writer, the inertia passes and the MuJoCo validator read meshes through here. This package
imports only :mod:`robodesc.ir`.

- :mod:`.data`: STL, plain OBJ and COLLADA to finished arrays without numpy (the C path);
- :mod:`.readers`: the numpy readers (broken STL, OBJ needing the line reader, no C compiler);
- :mod:`.collada`: the COLLADA reader (lxml; node transforms and instancing);
- :mod:`.text_numbers`: numbers in mesh text;
- :mod:`.mass`: volume, centre and inertia tensor of a mesh (trimesh's numbers, without trimesh);
- :mod:`.trimesh_io`: every other format, through trimesh.
"""
