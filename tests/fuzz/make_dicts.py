#!/usr/bin/env python3
"""Writes the libFuzzer dictionaries (material.dict, scene.dict, gltf.dict) from
the catalog, so the fuzzers know every key and model name facet reads.

    facet models --json | tests/fuzz/make_dicts.py tests/fuzz
"""
import json
import sys

JSON_TOKENS = ['{', '}', '[', ']', ':', ',', 'true', 'false', 'null', '-1e400', '1e-7', '0.0', '-0', '"\\u0000"']
GLTF_KEYS = ['asset', 'version', '2.0', 'scenes', 'scene', 'nodes', 'children', 'mesh', 'meshes', 'primitives',
             'attributes', 'POSITION', 'NORMAL', 'indices', 'mode', 'material', 'materials', 'accessors',
             'bufferView', 'bufferViews', 'buffer', 'buffers', 'byteOffset', 'byteLength', 'byteStride', 'uri',
             'componentType', 'count', 'type', 'VEC3', 'SCALAR', 'min', 'max', 'matrix', 'translation', 'rotation',
             'scale', 'camera', 'cameras', 'perspective', 'orthographic', 'yfov', 'znear', 'zfar', 'extensions',
             'extensionsUsed', 'extensionsRequired', 'pbrMetallicRoughness', 'baseColorFactor', 'metallicFactor',
             'roughnessFactor', 'emissiveFactor', 'KHR_lights_punctual', 'lights', 'light', 'intensity', 'color',
             'spot', 'innerConeAngle', 'outerConeAngle', 'range', 'point', 'directional', 'FACET_material',
             'FACET_object', 'FACET_light', 'FACET_scene', 'sphere', 'plane', 'center', 'radius', 'normal', 'size',
             'ambient', 'data:application/octet-stream;base64,', 'TEXCOORD_0', 'TEXCOORD_1', 'images', 'textures',
             'samplers', 'source', 'sampler', 'mimeType', 'image/png', 'image/jpeg', 'data:image/png;base64,',
             'baseColorTexture', 'metallicRoughnessTexture', 'normalTexture', 'emissiveTexture', 'occlusionTexture',
             'index', 'texCoord', 'KHR_texture_transform', 'magFilter', 'minFilter', 'wrapS', 'wrapT', '9728',
             '9729', '9987', '10497', '33071', '33648', 'TANGENT', 'COLOR_0', 'VEC4', 'strength', 'KHR_materials_emissive_strength',
             'emissiveStrength']


TEXTURE_KEYS = ['texture', 'channel', 'uv', 'transform', 'offset', 'scale', 'rotation', 'colorspace', 'srgb',
                'linear', 'filter', 'nearest', 'bilinear', 'wrap', 'repeat', 'clamp', 'mirror', 'factor', 'rgb',
                'r', 'g', 'b', 'a', 'textures/checker.png', 'textures/roughness16.png', 'texcoords',
                'texcoords1', 'tangents', 'colors', 'vertex_color', 'normal_map', 'green', 'up', 'down', 'strength',
                'textures/normals.png']
# What names and paths must survive (issue 28), as JSON string text: comment ends, a
# backslash, escaped line breaks (\n, \r, U+0085, U+2028), a quote, preprocessor and POV-Ray
# directives, paths leading out of the file's folder.
HOSTILE_TOKENS = ['*/', '/*', '//', '\\\\', '\\n', '\\r', '\\u0085', '\\u2028', '\\"', '#error', '#fopen',
                  '#include', '#declare', '#write', '../', '/proc/self/environ', '%2e%2e', '\\u0000']
IMAGE_TOKENS = ['\x89PNG\r\n\x1a\n', 'IHDR', 'IDAT', 'IEND', 'PLTE', 'tRNS', 'gAMA', 'sRGB', '\xff\xd8\xff',
                'P5', 'P6', 'BM', 'GIF89a', '8BPS', '\x00\x00\x00\x0d']


def names(catalog, sections):
    out = set()
    for section in sections:
        for model in catalog['sections'].get(section, []):
            out.add(model['name'])
            for p in model['parameters']:
                out.add(p['name'])
                for c in p.get('choices', []):
                    out.add(c)
    return out


def escape(word):
    """A libFuzzer dictionary entry: quoted, with \\, \" and \\xHH escapes."""
    out = ''
    for ch in word:
        if ch in '\\"':
            out += '\\' + ch
        elif ' ' <= ch <= '~':
            out += ch
        else:
            # Image signatures are bytes: a character below 256 is that byte.
            out += ''.join('\\x%02X' % b for b in (ch.encode('latin-1') if ord(ch) < 256 else ch.encode()))
    return '"' + out + '"'


def write(path, words):
    with open(path, 'w') as f:
        f.write('# Made by make_dicts.py from `facet models --json`; libFuzzer dictionary format.\n')
        for w in sorted(set(words)):
            f.write(escape(w) + '\n')


def main():
    folder = sys.argv[1]
    catalog = json.load(sys.stdin)
    shading = ['diffuse', 'specular', 'fresnel', 'geometry', 'modifier']
    material = names(catalog, shading) | {'model', 'name', 'ambient', 'emission', 'diffuse', 'specular',
                                          'tangent_axis', '$schema'} | set(TEXTURE_KEYS) | set(HOSTILE_TOKENS)
    scene = material | names(catalog, ['camera', 'object', 'light', 'attenuation']) | {
        'camera', 'objects', 'lights', 'materials', 'material', 'attenuation'}
    write(folder + '/material.dict', material | set(JSON_TOKENS))
    write(folder + '/scene.dict', scene | set(JSON_TOKENS))
    write(folder + '/gltf.dict', set(GLTF_KEYS) | material | set(JSON_TOKENS) | {'glTF', 'JSON', 'BIN\x00'})
    write(folder + '/texture.dict', set(IMAGE_TOKENS))


if __name__ == '__main__':
    main()
