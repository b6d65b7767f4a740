# The double gyre (Shadden, Lekien and Marsden 2005) at t = 0 on [0, 2] x [0, 1] as a 2D mesh of
# quads with a 2-component point velocity: a legacy ASCII .vtk.
import math, sys
nx, ny, A = 160, 80, 0.1
out = open(sys.argv[1], "w")
out.write("# vtk DataFile Version 4.2\ndouble gyre\nASCII\nDATASET UNSTRUCTURED_GRID\n")
out.write("POINTS %d double\n" % ((nx + 1) * (ny + 1)))
for j in range(ny + 1):
    for i in range(nx + 1):
        out.write("%.6g %.6g 0\n" % (2.0 * i / nx, 1.0 * j / ny))
out.write("CELLS %d %d\n" % (nx * ny, 5 * nx * ny))
for j in range(ny):
    for i in range(nx):
        a = j * (nx + 1) + i
        out.write("4 %d %d %d %d\n" % (a, a + 1, a + nx + 2, a + nx + 1))
out.write("CELL_TYPES %d\n" % (nx * ny) + "9\n" * (nx * ny))
out.write("POINT_DATA %d\nSCALARS velocity double 2\nLOOKUP_TABLE default\n" % ((nx + 1) * (ny + 1)))
for j in range(ny + 1):
    for i in range(nx + 1):
        x, y = 2.0 * i / nx, 1.0 * j / ny
        out.write("%.6g %.6g\n" % (-math.pi * A * math.sin(math.pi * x) * math.cos(math.pi * y),
                                   math.pi * A * math.cos(math.pi * x) * math.sin(math.pi * y)))
