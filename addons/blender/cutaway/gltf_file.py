"""The JSON of a cutaway glTF 2.0 file (.glb or .gltf) and what the importer reads from it.

Blender's glTF importer drops a few things cutaway writes (MSFT_lod, diffuse transmission, the
scene's exposure and sky); this module reads them from the file itself.
"""

import base64
import json
import os
import re
import struct
import urllib.parse

# The sky cutaway's studio scenes light with when a file with lights names none (lux).
DEFAULT_AMBIENT_LUX = 322.0

_GLB_MAGIC = b"glTF"
_CHUNK_JSON = 0x4E4F534A
_CHUNK_BIN = 0x004E4942
_LOD_NAME = re.compile(r"_LOD\d+$")
_COLLISION_PREFIXES = ("UCX_",)  # Unreal
_COLLISION_SUFFIXES = ("-convcolonly", "-colonly")  # Godot


def is_collision_name(name):
    """True for a node that holds a collision shape by its engine naming convention."""
    return name.startswith(_COLLISION_PREFIXES) or name.endswith(_COLLISION_SUFFIXES)


class GltfFile:
    """A glTF file's JSON document and, for a .glb, its binary chunk."""

    def __init__(self, path, document, binary=None):
        self.path = path
        self.json = document
        self.binary = binary

    @classmethod
    def load(cls, path):
        """Reads a .glb or .gltf file; raises ValueError when it is neither."""
        with open(path, "rb") as stream:
            data = stream.read()
        if data[:4] == _GLB_MAGIC:
            return cls._from_glb(path, data)
        try:
            return cls(path, json.loads(data.decode("utf-8")))
        except (UnicodeDecodeError, json.JSONDecodeError) as error:
            raise ValueError(f"{path}: not a glTF file ({error})") from None

    @classmethod
    def _from_glb(cls, path, data):
        document, binary = None, None
        offset = 12
        while offset + 8 <= len(data):
            length, kind = struct.unpack_from("<II", data, offset)
            chunk = data[offset + 8:offset + 8 + length]
            if kind == _CHUNK_JSON and document is None:
                document = json.loads(chunk.decode("utf-8"))
            elif kind == _CHUNK_BIN and binary is None:
                binary = chunk
            offset += 8 + length
        if document is None:
            raise ValueError(f"{path}: a .glb without a JSON chunk")
        return cls(path, document, binary)

    # The scene.

    @property
    def nodes(self):
        """The file's nodes (a list of dicts)."""
        return self.json.get("nodes", [])

    @property
    def scene(self):
        """The file's default scene (its first when none is named), or an empty dict."""
        scenes = self.json.get("scenes", [])
        index = self.json.get("scene", 0)
        return scenes[index] if 0 <= index < len(scenes) else {}

    @property
    def scene_extras(self):
        """The default scene's extras (exposure, ambient_lux), or an empty dict."""
        extras = self.scene.get("extras")
        return extras if isinstance(extras, dict) else {}

    @property
    def has_lights(self):
        """True when the file's scene uses KHR_lights_punctual lights."""
        lights = self.json.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights")
        return bool(lights) and any(
            "KHR_lights_punctual" in node.get("extensions", {}) for node in self.scene_nodes())

    def scene_nodes(self):
        """Indices of the nodes of the default scene, parents before their children."""
        order, stack = [], list(reversed(self.scene.get("nodes", [])))
        while stack:
            index = stack.pop()
            order.append(index)
            stack.extend(reversed(self.nodes[index].get("children", [])))
        return order

    def exposure(self):
        """The display value per unit of the lights' radiance (three.js's toneMappingExposure
        under linear tone mapping), or None when the file does not say."""
        value = self.scene_extras.get("exposure")
        return float(value) if isinstance(value, (int, float)) and value > 0 else None

    def ambient_lux(self):
        """Illuminance in lux of the uniform sky the scene expects, or None for none.

        A file that describes its view (exposure) names its sky, or has none; older files with
        lights get cutaway's studio sky; assets without lights get none.
        """
        extras = self.scene_extras
        value = extras.get("ambient_lux")
        if isinstance(value, (int, float)):
            return float(value) if value > 0 else None
        if "exposure" in extras or not self.has_lights:
            return None
        return DEFAULT_AMBIENT_LUX

    def camera_node(self):
        """Index of the first node of the scene that holds a camera, or None."""
        return next((i for i in self.scene_nodes() if "camera" in self.nodes[i]), None)

    def camera_aspect_ratio(self, node_index):
        """The aspectRatio of the perspective camera of this node, or None."""
        camera = self.json.get("cameras", [])[self.nodes[node_index]["camera"]]
        value = camera.get("perspective", {}).get("aspectRatio")
        return float(value) if isinstance(value, (int, float)) else None

    # Levels of detail and collision shapes.

    def lod_nodes(self):
        """Maps the index of each coarser level-of-detail node to the index of the node it
        stands in for: the nodes MSFT_lod lists, and nodes named NAME_LOD<digits> whose full
        level is named NAME_mesh or NAME."""
        lods = {}
        for index, node in enumerate(self.nodes):
            for lod in node.get("extensions", {}).get("MSFT_lod", {}).get("ids", []):
                lods[lod] = index
        by_name = {node.get("name"): index for index, node in enumerate(self.nodes)}
        for index, node in enumerate(self.nodes):
            name = node.get("name", "")
            if index in lods or not _LOD_NAME.search(name):
                continue
            stem = _LOD_NAME.sub("", name)
            base = by_name.get(stem + "_mesh", by_name.get(stem))
            if base is not None and base != index:
                lods[index] = base
        return lods

    def collision_nodes(self):
        """Indices of the nodes named as collision shapes."""
        return [i for i, node in enumerate(self.nodes) if is_collision_name(node.get("name", ""))]

    # Materials and images.

    def image_of_texture(self, texture_index):
        """Index of the image a texture samples, or None."""
        textures = self.json.get("textures", [])
        if not 0 <= texture_index < len(textures):
            return None
        return textures[texture_index].get("source")

    def image_name(self, image_index):
        """The name Blender's importer gives an image (its glTF name, else Image_N)."""
        return self.json["images"][image_index].get("name") or f"Image_{image_index}"

    def image_bytes(self, image_index):
        """The encoded bytes (PNG or JPEG) of an image: from the binary chunk, a data URI or a
        file next to the .gltf."""
        image = self.json["images"][image_index]
        if "bufferView" in image:
            view = self.json["bufferViews"][image["bufferView"]]
            if view.get("buffer", 0) != 0 or self.binary is None:
                raise ValueError(f"{self.path}: image {image_index} is not in the .glb's chunk")
            start = view.get("byteOffset", 0)
            return self.binary[start:start + view["byteLength"]]
        uri = image.get("uri", "")
        if uri.startswith("data:"):
            return base64.b64decode(uri.split(",", 1)[1])
        path = os.path.join(os.path.dirname(self.path), urllib.parse.unquote(uri))
        with open(path, "rb") as stream:
            return stream.read()
