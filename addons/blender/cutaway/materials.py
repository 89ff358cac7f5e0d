"""Translucent cut flesh: KHR_materials_diffuse_transmission, which Blender's importer drops,
wired into the Principled BSDF as subsurface scattering.

The weight is the extension's diffuseTransmissionFactor times the alpha channel of its
diffuseTransmissionTexture (where the extension keeps the factor map); the scattered light takes
the base colour and travels as far as the material's extras say (`subsurface_radius_m`: red,
green, blue in metres, which cutaway derives from the template's translucency, size and dark
seeds), or a few millimetres in a file without them.
"""

import math

import bpy

from .hierarchy import base_name

EXTENSION = "KHR_materials_diffuse_transmission"

# Mean free path per red, green and blue channel in metres where the file does not give one:
# light in fruit flesh travels a few millimetres, red the furthest.
SUBSURFACE_RADIUS = (0.004, 0.0025, 0.0015)


def add_translucency(gltf, new_materials, new_images):
    """Wires the diffuse transmission of every material of the file that has it into the
    Principled BSDF of the Blender materials made from it. Returns those Blender materials."""
    by_name = {}
    for material in new_materials:
        by_name.setdefault(base_name(material.name), []).append(material)
    wired = []
    for index, gltf_material in enumerate(gltf.json.get("materials", [])):
        extension = gltf_material.get("extensions", {}).get(EXTENSION)
        if extension is None:
            continue
        name = gltf_material.get("name") or f"Material_{index}"
        radius = subsurface_radius(gltf_material)
        for material in by_name.get(name, []):
            if _wire(gltf, material, extension, new_images, radius):
                wired.append(material)
    return wired


def subsurface_radius(gltf_material):
    """The glTF material's extras.subsurface_radius_m (three numbers above 0 and at most 1 m),
    else SUBSURFACE_RADIUS: the file is read as untrusted input."""
    extras = gltf_material.get("extras")
    radius = extras.get("subsurface_radius_m") if isinstance(extras, dict) else None
    if (isinstance(radius, list) and len(radius) == 3 and
            all(isinstance(r, (int, float)) and not isinstance(r, bool) and
                math.isfinite(r) and 0 < r <= 1 for r in radius)):
        return tuple(float(r) for r in radius)
    return SUBSURFACE_RADIUS


def principled_bsdf(material):
    """The Principled BSDF feeding the material's output, or None."""
    if not material.use_nodes:
        return None
    for node in material.node_tree.nodes:
        if node.type == 'OUTPUT_MATERIAL' and node.is_active_output:
            for link in node.inputs["Surface"].links:
                if link.from_node.type == 'BSDF_PRINCIPLED':
                    return link.from_node
    return next((n for n in material.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'), None)


def subsurface_weight_input(bsdf):
    """The Principled BSDF's subsurface weight socket (Blender 3.x 'Subsurface', 4.x
    'Subsurface Weight')."""
    return _input(bsdf, "Subsurface Weight", "Subsurface")


def _input(node, *names):
    return next((node.inputs[n] for n in names if n in node.inputs), None)


def _wire(gltf, material, extension, new_images, radius):
    factor = float(extension.get("diffuseTransmissionFactor", 0.0))
    texture = extension.get("diffuseTransmissionTexture")
    bsdf = principled_bsdf(material)
    weight = subsurface_weight_input(bsdf) if bsdf else None
    if weight is None or factor <= 0:
        return False
    tree = material.node_tree
    alpha = _texture_alpha(gltf, tree, texture, new_images) if texture else None
    if alpha is None:
        weight.default_value = min(factor, 1.0)
    elif factor >= 1.0:
        tree.links.new(alpha, weight)
    else:
        multiply = tree.nodes.new("ShaderNodeMath")
        multiply.operation = 'MULTIPLY'
        multiply.label = "Diffuse Transmission"
        multiply.location = bsdf.location.x - 200, bsdf.location.y - 400
        multiply.inputs[1].default_value = factor
        tree.links.new(alpha, multiply.inputs[0])
        tree.links.new(multiply.outputs[0], weight)
    _set_radius(bsdf, radius)
    _set_method(bsdf)
    _copy_base_colour_to_subsurface(tree, bsdf)
    if hasattr(material, "use_sss_translucency"):  # Eevee Legacy: light through thin parts
        material.use_sss_translucency = True
    return True


def _set_radius(bsdf, radius):
    """Sets the BSDF's subsurface radius (red, green, blue; metres)."""
    scale_input = _input(bsdf, "Subsurface Scale")
    radius_input = _input(bsdf, "Subsurface Radius")
    largest = max(radius)
    if scale_input is not None:  # Blender 4: radius per channel times the scale
        scale_input.default_value = largest
        if radius_input is not None:
            radius_input.default_value = [r / largest for r in radius]
    elif radius_input is not None:
        radius_input.default_value = radius


# Cycles' subsurface method where the BSDF offers it (Blender 3.x): the random walk with a fixed
# radius is about a third less noisy in the flesh than the default random walk at the add-on's
# sampling (the persimmon's cut face on the halves board: 2.9 against 4.5 of 255 between two
# seeds) and as fast, with the same mean colour.
SUBSURFACE_METHOD = 'RANDOM_WALK_FIXED_RADIUS'


def _set_method(bsdf):
    methods = {item.identifier for item in bsdf.bl_rna.properties["subsurface_method"].enum_items} \
        if "subsurface_method" in bsdf.bl_rna.properties else set()
    if SUBSURFACE_METHOD in methods:
        bsdf.subsurface_method = SUBSURFACE_METHOD


def _copy_base_colour_to_subsurface(tree, bsdf):
    """Blender 3.x scatters a colour of its own; give it the base colour (4.x uses that)."""
    colour = _input(bsdf, "Subsurface Color")
    base = bsdf.inputs["Base Color"]
    if colour is None:
        return
    if base.links:
        tree.links.new(base.links[0].from_socket, colour)
    else:
        colour.default_value = base.default_value


def _texture_alpha(gltf, tree, texture, new_images):
    """The Alpha output of an Image Texture node sampling the texture: the importer's own node
    where the material already samples that image (the metallic-roughness map, usually), else a
    new node, loading the image from the file if the importer did not."""
    image_index = gltf.image_of_texture(texture.get("index", -1))
    if image_index is None:
        return None
    name = gltf.image_name(image_index)
    for node in tree.nodes:
        if node.type == 'TEX_IMAGE' and node.image and base_name(node.image.name) == name:
            return node.outputs["Alpha"]
    image = next((i for i in new_images if base_name(i.name) == name), None)
    if image is None:
        image = _load_image(gltf, image_index, name)
        new_images.append(image)
    node = tree.nodes.new("ShaderNodeTexImage")
    node.image = image
    node.label = "Diffuse Transmission"
    uv_index = texture.get("texCoord", 0)
    if uv_index:
        uv = tree.nodes.new("ShaderNodeUVMap")
        uv.uv_map = "UVMap.%03d" % uv_index  # the importer's names for UV sets past the first
        tree.links.new(uv.outputs["UV"], node.inputs["Vector"])
    return node.outputs["Alpha"]


def _load_image(gltf, image_index, name):
    """An image of the file as a new image packed into the .blend; its alpha is data."""
    data = gltf.image_bytes(image_index)
    image = bpy.data.images.new(name, 8, 8, alpha=True)
    image.pack(data=data, data_len=len(data))
    image.source = 'FILE'
    image.colorspace_settings.name = "Non-Color"
    return image
