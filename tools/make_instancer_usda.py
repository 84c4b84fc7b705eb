#!/usr/bin/python3
"""Writes a USD stage with one PointInstancer of N instances to stdout, for
measuring instancing (docs/usd.md, "PointInstancer"):

  tools/make_instancer_usda.py 100000 > /tmp/scatter.usda

Two labelled prototypes beneath the instancer (a 12-triangle box Mesh and a
Cube), instances on a square grid seen from above, each turned about Z
(quath orientations) and scaled, ids authored, a camera and a light.
"""
import math
import sys


def main():
    if len(sys.argv) != 2 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit("usage: make_instancer_usda.py COUNT  (a whole number >= 1)")
    n = int(sys.argv[1])
    side = math.ceil(math.sqrt(n))
    spacing = 40.0 / side
    positions, orientations, scales, indices = [], [], [], []
    for i in range(n):
        x = -20 + spacing * (i % side + 0.5)
        y = -20 + spacing * (i // side + 0.5)
        half = math.radians(i * 7 % 360) / 2
        positions.append(f"({x:.4f}, {y:.4f}, 0)")
        orientations.append(f"({math.cos(half):.5f}, 0, 0, {math.sin(half):.5f})")
        s = spacing * (0.15 + 0.05 * (i % 3))
        scales.append(f"({s:.4f}, {s:.4f}, {s:.4f})")
        indices.append(str(i % 2))
    out = sys.stdout
    out.write('#usda 1.0\n(\n    defaultPrim = "World"\n    metersPerUnit = 1\n    upAxis = "Z"\n)\n\n')
    out.write('def Xform "World"\n{\n    def PointInstancer "Scatter"\n    {\n')
    out.write('        rel prototypes = [</World/Scatter/Prototypes/Box>, </World/Scatter/Prototypes/Crate>]\n')
    out.write(f'        int[] protoIndices = [{", ".join(indices)}]\n')
    out.write(f'        int64[] ids = [{", ".join(str(i) for i in range(n))}]\n')
    out.write(f'        point3f[] positions = [{", ".join(positions)}]\n')
    out.write(f'        quath[] orientations = [{", ".join(orientations)}]\n')
    out.write(f'        float3[] scales = [{", ".join(scales)}]\n')
    out.write('''
        def Scope "Prototypes"
        {
            def Mesh "Box" (
                prepend apiSchemas = ["SemanticsAPI:Semantics_a1"]
            )
            {
                string semantic:Semantics_a1:params:semanticType = "class"
                string semantic:Semantics_a1:params:semanticData = "box"
                point3f[] points = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]
                int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]
                int[] faceVertexIndices = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7]
                uniform token subdivisionScheme = "none"
                color3f[] primvars:displayColor = [(0.8, 0.5, 0.2)]
            }

            def Cube "Crate" (
                prepend apiSchemas = ["SemanticsAPI:Semantics_a1"]
            )
            {
                string semantic:Semantics_a1:params:semanticType = "class"
                string semantic:Semantics_a1:params:semanticData = "crate"
                double size = 1.5
                color3f[] primvars:displayColor = [(0.2, 0.4, 0.8)]
            }
        }
    }

    def Camera "Cam"
    {
        float focalLength = 18
        float2 clippingRange = (0.1, 200)
        double3 xformOp:translate = (0, 0, 40)
        uniform token[] xformOpOrder = ["xformOp:translate"]
    }

    def DistantLight "Sun"
    {
        float inputs:intensity = 3000
        float3 xformOp:rotateXYZ = (20, 10, 0)
        uniform token[] xformOpOrder = ["xformOp:rotateXYZ"]
    }
}
''')


if __name__ == "__main__":
    main()
