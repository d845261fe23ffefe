"""A GLB with one mesh decimated to about a given face count, for measuring a garment of
another density (bench/results/animation.md).

Seam copies (one position, several UVs) are welded first, so that both sides of a seam
collapse alike; each kept vertex then takes the skin, normal and UV of its nearest
original vertex. Every other part of the file is copied as it is.

    python3 bench/decimate_glb_mesh.py IN.glb MESH FACES OUT.glb

Needs numpy, scipy, pygltflib and fast-simplification (PyPI).
"""
import sys

import fast_simplification
import numpy as np
import pygltflib
from scipy.spatial import cKDTree

DTYPES = {5126: np.float32, 5125: np.uint32, 5123: np.uint16, 5121: np.uint8}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


class Glb:
    def __init__(self, path):
        self.gltf = pygltflib.GLTF2().load(path)
        self.blob = bytearray(self.gltf.binary_blob())

    def read(self, accessor):
        a = self.gltf.accessors[accessor]
        view = self.gltf.bufferViews[a.bufferView]
        dtype = np.dtype(DTYPES[a.componentType])
        width = WIDTH[a.type]
        start = (view.byteOffset or 0) + (a.byteOffset or 0)
        stride = view.byteStride or dtype.itemsize * width
        rows = np.lib.stride_tricks.as_strided(
            np.frombuffer(self.blob, dtype, offset=start),
            shape=(a.count, width), strides=(stride, dtype.itemsize))
        return np.array(rows)

    def append(self, values, component_type, kind, target):
        data = np.ascontiguousarray(values, DTYPES[component_type]).tobytes()
        while len(self.blob) % 4:
            self.blob.append(0)
        self.gltf.bufferViews.append(pygltflib.BufferView(
            buffer=0, byteOffset=len(self.blob), byteLength=len(data), target=target))
        self.blob += data
        accessor = pygltflib.Accessor(bufferView=len(self.gltf.bufferViews) - 1,
                                      componentType=component_type, count=len(values), type=kind)
        if kind == "VEC3" and component_type == 5126:
            accessor.min, accessor.max = values.min(0).tolist(), values.max(0).tolist()
        self.gltf.accessors.append(accessor)
        return len(self.gltf.accessors) - 1

    def save(self, path):
        self.gltf.buffers[0].byteLength = len(self.blob)
        self.gltf.set_binary_blob(bytes(self.blob))
        self.gltf.save_binary(path)


def main(source, mesh_name, faces_wanted, out):
    glb = Glb(source)
    mesh = next(m for m in glb.gltf.meshes if m.name == mesh_name)
    if len(mesh.primitives) != 1:
        sys.exit(f"{mesh_name}: one primitive expected")
    primitive = mesh.primitives[0]
    positions = glb.read(primitive.attributes.POSITION).astype(np.float64)
    faces = glb.read(primitive.indices).reshape(-1, 3).astype(np.int64)

    _, first, welded = np.unique(positions.round(7), axis=0, return_index=True,
                                 return_inverse=True)
    faces = welded.reshape(-1)[faces]
    faces = faces[(faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) &
                  (faces[:, 0] != faces[:, 2])]
    points, kept_faces = fast_simplification.simplify(
        positions[first].astype(np.float32), faces.astype(np.int32),
        target_reduction=1.0 - faces_wanted / len(faces))
    nearest = first[cKDTree(positions[first]).query(points)[1]]
    print(f"{mesh_name}: {len(faces)} faces welded, {len(kept_faces)} kept, "
          f"{len(points)} vertices")

    attributes = primitive.attributes
    attributes.POSITION = glb.append(points.astype(np.float32), 5126, "VEC3", ARRAY_BUFFER)
    for name, kind in [("NORMAL", "VEC3"), ("TEXCOORD_0", "VEC2"), ("JOINTS_0", "VEC4"),
                       ("WEIGHTS_0", "VEC4")]:
        accessor = getattr(attributes, name)
        if accessor is not None:
            component_type = glb.gltf.accessors[accessor].componentType
            setattr(attributes, name, glb.append(glb.read(accessor)[nearest], component_type,
                                                 kind, ARRAY_BUFFER))
    primitive.indices = glb.append(kept_faces.reshape(-1), 5125, "SCALAR", ELEMENT_ARRAY_BUFFER)
    primitive.targets = None
    glb.save(out)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4])
