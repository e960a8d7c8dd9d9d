#!/usr/bin/env python3
"""Writes the seed corpus of the 3MF fuzz target (fuzz_3mf) into OUT_DIR: small 3MF packages,
stored and deflated, as lib3mf, PrusaSlicer and Bambu Studio / OrcaSlicer lay them out, and
broken ones. Generated here so that no third-party file is committed.

Files named ok-*.3mf must load; bad-*.3mf must fail with a message (tests/geometry/plate checks
both). Usage: make_3mf_corpus.py OUT_DIR
"""
import io
import os
import sys
import zipfile

NS = ('xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" '
      'xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06"')
TYPES = ('<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/'
         'content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.'
         'relationships+xml"/><Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-'
         '3dmodel+xml"/><Default Extension="config" ContentType="text/xml"/></Types>')
RELS = ('<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/'
        'relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" '
        'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')
FACES = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
         (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]


def box(sx, sy, sz, x0=0.0):
    v = ''.join(f'<vertex x="{x0 + x * sx}" y="{y * sy}" z="{z * sz}"/>'
                for z in (0, 1) for y in (0, 1) for x in (0, 1))
    t = ''.join(f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in FACES)
    return f'<mesh><vertices>{v}</vertices><triangles>{t}</triangles></mesh>'


def model(resources, build, unit='millimeter', extra=''):
    return (f'<?xml version="1.0" encoding="UTF-8"?><model unit="{unit}" {NS}{extra}>'
            f'<resources>{resources}</resources><build>{build}</build></model>')


def package(files, deflate=True):
    out = io.BytesIO()
    with zipfile.ZipFile(out, 'w', zipfile.ZIP_DEFLATED if deflate else zipfile.ZIP_STORED) as z:
        for name, content in files:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED if deflate else zipfile.ZIP_STORED
            z.writestr(info, content)
    return out.getvalue()


def plain(m, extra=(), deflate=True):
    return package([('[Content_Types].xml', TYPES), ('_rels/.rels', RELS), ('3D/3dmodel.model', m)] + list(extra),
                   deflate)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    cube = model(f'<object id="1" name="cube" type="model">{box(10, 10, 10)}</object>',
                 '<item objectid="1" transform="1 0 0 0 1 0 0 0 1 50 50 0"/>')
    two_items = model(f'<object id="1" name="bar" type="model">{box(40, 10, 5)}</object>',
                      '<item objectid="1" transform="0 1 0 -1 0 0 0 0 1 60 80 0"/>'
                      '<item objectid="1" transform="1 0 0 0 1 0 0 0 1 100 80 3"/>')
    components = model(f'<object id="1" name="part" type="model">{box(5, 5, 5)}</object>'
                       '<object id="2" name="pair" type="model"><components><component objectid="1"/>'
                       '<component objectid="1" transform="-1 0 0 0 1 0 0 0 1 20 0 0"/></components></object>',
                       '<item objectid="2"/>', unit='centimeter')
    prusa_config = ('<?xml version="1.0"?><config><object id="1" instances_count="1">'
                    '<metadata type="object" key="name" value="cube"/>'
                    '<metadata type="object" key="fill_density" value="40%"/>'
                    '<volume firstid="0" lastid="11"><metadata type="volume" key="volume_type" value="ModelPart"/>'
                    '</volume></object></config>')
    bambu_root = model('<object id="3" type="model"><components>'
                       '<component p:path="/3D/Objects/object_1.model" objectid="1"/>'
                       '<component p:path="/3D/Objects/object_1.model" objectid="2"/></components></object>',
                       '<item objectid="3" transform="1 0 0 0 1 0 0 0 1 100 100 0"/>', extra=' requiredextensions="p"')
    bambu_part = model(f'<object id="1" type="model">{box(10, 10, 10)}</object>'
                       f'<object id="2" type="model">{box(3, 3, 3, 2)}</object>', '')
    bambu_settings = ('<?xml version="1.0"?><config><object id="3"><metadata key="name" value="Widget"/>'
                      '<part id="1" subtype="normal_part"/><part id="2" subtype="modifier_part"/></object></config>')
    seeds = {
        'ok-cube.3mf': plain(cube),
        'ok-cube-stored.3mf': plain(cube, deflate=False),
        'ok-two-items.3mf': plain(two_items),
        'ok-components.3mf': plain(components),
        'ok-prusa.3mf': plain(cube, [('Metadata/Slic3r_PE_model.config', prusa_config),
                                     ('Metadata/Slic3r_PE.config', '; layer_height = 0.2\n')]),
        'ok-bambu.3mf': plain(bambu_root, [('3D/Objects/object_1.model', bambu_part),
                                           ('Metadata/model_settings.config', bambu_settings)]),
        'bad-truncated.3mf': plain(cube)[:300],
        'bad-no-model.3mf': package([('[Content_Types].xml', TYPES), ('_rels/.rels', RELS)]),
        'bad-not-3mf.3mf': package([('readme.txt', 'hello'), ('part.stl', 'solid x\nendsolid x\n')]),
        'bad-xml.3mf': plain(cube[:len(cube) - 40]),
        'bad-index.3mf': plain(cube.replace('v3="1"', 'v3="99"', 1)),
        'bad-flat.3mf': plain(cube.replace('1 0 0 0 1 0 0 0 1 50 50 0', '1 0 0 0 1 0 0 0 0 50 50 0')),
        'bad-missing-part.3mf': plain(bambu_root, [('3D/Objects/other.model', bambu_part)]),
    }
    for name, data in seeds.items():
        with open(os.path.join(out, name), 'wb') as f:
            f.write(data if isinstance(data, bytes) else data.encode())


if __name__ == '__main__':
    main()
