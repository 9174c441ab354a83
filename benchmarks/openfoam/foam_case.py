"""Write an OpenFOAM (v1912, Debian's `openfoam`) case for a box with
spherical grains: blockMesh background mesh, snappyHexMesh body-fitted mesh
around the spheres (analytic `searchableSphere` surfaces, no STL), simpleFoam
(steady, laminar, SIMPLEC), the force on the grains and the mean pressure on
cutting planes as function objects.

Everything is in SI units; OpenFOAM's incompressible solvers work with the
kinematic pressure p / rho, which the readers below convert back.

Used by scripts/benchmarks/benchmark_vs_openfoam.py; see benchmarks/openfoam/README.md.
"""
import glob
import os
import re

HEADER = """FoamFile
{
    version 2.0;
    format ascii;
    class %s;
    object %s;
}
"""

FACES = {
    # blockMesh face of the hex (0 0 0)-(1 1 1) vertex ordering below
    'x min': '(0 4 7 3)', 'x max': '(1 2 6 5)',
    'y min': '(0 1 5 4)', 'y max': '(3 7 6 2)',
    'z min': '(0 3 2 1)', 'z max': '(4 5 6 7)',
}
PATCH = {f: f.replace(' ', '_') for f in FACES}


def write(path, text, cls='dictionary'):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(HEADER % (cls, os.path.basename(path)) + text)


def vec(v):
    return '(%.9g %.9g %.9g)' % tuple(v)


class Case:
    """A box [lo, hi] with spheres (x, y, z, r), a uniform background mesh of
    @p blocks cells per direction, refined @p level times at the sphere
    surfaces (the smallest cell is (hi - lo) / blocks / 2^level).

    @p faces maps each box face ('x min', ...) to one of
      ('velocity', (ux, uy, uz)), ('flow rate', Q) (uniform inflow),
      ('pressure', 0), ('symmetry', None), ('no slip', None).
    @p planes: positions along the flow @p axis (0, 1, 2) of cutting planes
    whose area-averaged pressure is written.
    @p mantle_radius: the fluid is the inside of a cylinder of that radius
    along @p axis through the box's centre (an analytic surface, refined
    like the grains, a no-slip wall `mantle`); the box outside it is cut.
    """

    def __init__(self, lo, hi, blocks, spheres, level, faces, nu, rho,
                 planes=(), inside=None, end_iteration=20000,
                 tolerance=(1e-7, 1e-8), second_order_convection=False,
                 ranks=1, axis=0, mantle_radius=None):
        self.lo, self.hi, self.blocks = lo, hi, blocks
        self.spheres, self.level, self.faces = spheres, level, faces
        self.nu, self.rho, self.planes = nu, rho, planes
        self.axis, self.mantle_radius = axis, mantle_radius
        self.inside = inside
        self.end_iteration = end_iteration
        self.tolerance = tolerance
        self.second_order_convection = second_order_convection
        self.ranks = ranks

    def smallest_cell(self):
        return (self.hi[0] - self.lo[0]) / self.blocks[0] / 2 ** self.level

    def write(self, directory):
        self.directory = directory
        self._block_mesh()
        self._snappy()
        self._fields()
        self._system()
        write(os.path.join(directory, 'constant', 'transportProperties'),
              'transportModel Newtonian;\nnu %.9g;\n' % self.nu)
        write(os.path.join(directory, 'constant', 'turbulenceProperties'),
              'simulationType laminar;\n')

    def _block_mesh(self):
        lo, hi = self.lo, self.hi
        pts = [(lo[0], lo[1], lo[2]), (hi[0], lo[1], lo[2]),
               (hi[0], hi[1], lo[2]), (lo[0], hi[1], lo[2]),
               (lo[0], lo[1], hi[2]), (hi[0], lo[1], hi[2]),
               (hi[0], hi[1], hi[2]), (lo[0], hi[1], hi[2])]
        patches = []
        for face, (kind, _) in self.faces.items():
            ptype = {'symmetry': 'symmetryPlane', 'no slip': 'wall'}.get(
                kind, 'patch')
            patches.append('    %s { type %s; faces (%s); }' % (
                PATCH[face], ptype, FACES[face]))
        text = ('convertToMeters 1;\nvertices\n(\n%s\n);\n'
                'blocks\n(\n    hex (0 1 2 3 4 5 6 7) (%d %d %d) '
                'simpleGrading (1 1 1)\n);\nedges ();\n'
                'boundary\n(\n%s\n);\n' % (
                    '\n'.join('    ' + vec(p) for p in pts),
                    self.blocks[0], self.blocks[1], self.blocks[2],
                    '\n'.join(patches)))
        write(os.path.join(self.directory, 'system', 'blockMeshDict'), text)

    def _snappy(self):
        geometry, surfaces = [], []
        for i, (x, y, z, r) in enumerate(self.spheres):
            geometry.append('    grain%d { type searchableSphere; '
                            'centre %s; radius %.9g; }' % (i, vec((x, y, z)), r))
            surfaces.append('        grain%d { level (%d %d); '
                            'patchInfo { type wall; } }' % (
                                i, self.level, self.level))
        if self.mantle_radius:
            centre = [(a + b) / 2 for a, b in zip(self.lo, self.hi)]
            ends = [list(centre), list(centre)]
            length = self.hi[self.axis] - self.lo[self.axis]
            ends[0][self.axis] = self.lo[self.axis] - length
            ends[1][self.axis] = self.hi[self.axis] + length
            geometry.insert(0, '    mantle { type searchableCylinder; '
                            'point1 %s; point2 %s; radius %.9g; }' % (
                                vec(ends[0]), vec(ends[1]),
                                self.mantle_radius))
            surfaces.insert(0, '        mantle { level (%d %d); '
                            'patchInfo { type wall; } }' % (self.level,
                                                            self.level))
        inside = self.inside or self._point_in_fluid()
        text = """castellatedMesh true;
snap true;
addLayers false;
geometry
{
%s
}
castellatedMeshControls
{
    maxLocalCells 100000000;
    maxGlobalCells 200000000;
    minRefinementCells 0;
    maxLoadUnbalance 0.10;
    nCellsBetweenLevels 3;
    features ();
    refinementSurfaces
    {
%s
    }
    resolveFeatureAngle 30;
    refinementRegions {}
    locationInMesh %s;
    allowFreeStandingZoneFaces true;
}
snapControls
{
    nSmoothPatch 3;
    tolerance 2.0;
    nSolveIter 100;
    nRelaxIter 5;
    nFeatureSnapIter 10;
    implicitFeatureSnap false;
    explicitFeatureSnap false;
    multiRegionFeatureSnap false;
}
addLayersControls
{
    relativeSizes true;
    layers {}
    expansionRatio 1.0;
    finalLayerThickness 0.3;
    minThickness 0.1;
    nGrow 0;
    featureAngle 60;
    nRelaxIter 3;
    nSmoothSurfaceNormals 1;
    nSmoothNormals 3;
    nSmoothThickness 10;
    maxFaceThicknessRatio 0.5;
    maxThicknessToMedialRatio 0.3;
    minMedialAxisAngle 90;
    nBufferCellsNoExtrude 0;
    nLayerIter 50;
}
meshQualityControls
{
    // the cells here are micrometres: no absolute volume or area limit
    maxNonOrtho 65;
    maxBoundarySkewness 20;
    maxInternalSkewness 4;
    maxConcave 80;
    minVol -1e30;
    minTetQuality 1e-15;
    minArea -1;
    minTwist 0.02;
    minDeterminant 0.001;
    minFaceWeight 0.05;
    minVolRatio 0.01;
    minTriangleTwist -1;
    nSmoothScale 4;
    errorReduction 0.75;
}
mergeTolerance 1e-6;
""" % ('\n'.join(geometry), '\n'.join(surfaces), vec(inside))
        write(os.path.join(self.directory, 'system', 'snappyHexMeshDict'),
              text)

    def _point_in_fluid(self):
        """A point of the box outside every sphere and off cell faces."""
        lo, hi = self.lo, self.hi
        for fx in (0.013, 0.987, 0.5013, 0.2513, 0.7513):
            for fy in (0.0137, 0.9863, 0.5137):
                for fz in (0.0171, 0.9829, 0.5171):
                    p = (lo[0] + fx * (hi[0] - lo[0]),
                         lo[1] + fy * (hi[1] - lo[1]),
                         lo[2] + fz * (hi[2] - lo[2]))
                    if all((p[0] - x) ** 2 + (p[1] - y) ** 2 +
                           (p[2] - z) ** 2 > (1.05 * r) ** 2
                           for x, y, z, r in self.spheres):
                        return p
        raise ValueError('no point of the box outside the grains found')

    def _fields(self):
        u_bc, p_bc = [], []
        for face, (kind, value) in self.faces.items():
            name = PATCH[face]
            if kind == 'velocity':
                u_bc.append('%s { type fixedValue; value uniform %s; }' % (
                    name, vec(value)))
                p_bc.append('%s { type zeroGradient; }' % name)
            elif kind == 'flow rate':
                u_bc.append('%s { type flowRateInletVelocity; '
                            'volumetricFlowRate constant %.9g; '
                            'value uniform (0 0 0); }' % (name, value))
                p_bc.append('%s { type zeroGradient; }' % name)
            elif kind == 'pressure':
                u_bc.append('%s { type inletOutlet; inletValue uniform '
                            '(0 0 0); value uniform (0 0 0); }' % name)
                p_bc.append('%s { type fixedValue; value uniform %.9g; }' % (
                    name, value / self.rho))
            elif kind == 'symmetry':
                u_bc.append('%s { type symmetryPlane; }' % name)
                p_bc.append('%s { type symmetryPlane; }' % name)
            else:
                u_bc.append('%s { type noSlip; }' % name)
                p_bc.append('%s { type zeroGradient; }' % name)
        walls = '"(grain.*|mantle)"' if self.mantle_radius else '"grain.*"'
        u_bc.append('%s { type noSlip; }' % walls)
        p_bc.append('%s { type zeroGradient; }' % walls)
        start = (0, 0, 0)
        for kind, value in self.faces.values():
            if kind == 'velocity':
                start = value
        write(os.path.join(self.directory, '0', 'U'),
              'dimensions [0 1 -1 0 0 0 0];\ninternalField uniform %s;\n'
              'boundaryField\n{\n    '
              '#includeEtc "caseDicts/setConstraintTypes"\n    %s\n}\n' % (vec(start),
                                                  '\n    '.join(u_bc)),
              'volVectorField')
        write(os.path.join(self.directory, '0', 'p'),
              'dimensions [0 2 -2 0 0 0 0];\ninternalField uniform 0;\n'
              'boundaryField\n{\n    '
              '#includeEtc "caseDicts/setConstraintTypes"\n    %s\n}\n' % '\n    '.join(p_bc),
              'volScalarField')

    def _system(self):
        d = self.directory
        planes = ''
        for i, x in enumerate(self.planes):
            point, normal = [0, 0, 0], [0, 0, 0]
            point[self.axis], normal[self.axis] = x, 1
            planes += """    plane%d
    {
        type surfaceFieldValue;
        libs ("libfieldFunctionObjects.so");
        regionType sampledSurface;
        name plane%d;
        sampledSurfaceDict
        {
            type cuttingPlane;
            planeType pointAndNormal;
            pointAndNormalDict { point %s; normal %s; }
            interpolate false;
        }
        operation areaAverage;
        fields (p);
        writeFields false;
        writeControl timeStep;
        writeInterval 10;
        log false;
    }
""" % (i, i, vec(point), vec(normal))
        forces = """    forces
    {
        type forces;
        libs ("libforces.so");
        patches ("grain.*");
        rho rhoInf;
        rhoInf %.9g;
        CofR (0 0 0);
        writeControl timeStep;
        writeInterval 10;
        log false;
    }
""" % self.rho
        write(os.path.join(d, 'system', 'controlDict'), """application simpleFoam;
startFrom latestTime;
startTime 0;
stopAt endTime;
endTime %d;
deltaT 1;
writeControl timeStep;
writeInterval %d;
purgeWrite 1;
writeFormat binary;
writePrecision 10;
timePrecision 8;
runTimeModifiable false;
functions
{
%s%s}
""" % (self.end_iteration, self.end_iteration, forces, planes))
        convection = ('bounded Gauss linearUpwind grad(U)'
                      if self.second_order_convection
                      else 'bounded Gauss linear')
        write(os.path.join(d, 'system', 'fvSchemes'), """ddtSchemes { default steadyState; }
gradSchemes { default Gauss linear; }
divSchemes
{
    default none;
    div(phi,U) %s;
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear limited corrected 0.5; }
interpolationSchemes { default linear; }
snGradSchemes { default limited corrected 0.5; }
""" % convection)
        write(os.path.join(d, 'system', 'fvSolution'), """solvers
{
    p
    {
        solver GAMG;
        smoother GaussSeidel;
        tolerance 1e-12;
        relTol 0.01;
    }
    "(U|Phi)"
    {
        solver smoothSolver;
        smoother symGaussSeidel;
        tolerance 1e-14;
        relTol 0.1;
    }
}
SIMPLE
{
    consistent yes;
    nNonOrthogonalCorrectors 1;
    residualControl { p %g; U %g; }
}
relaxationFactors
{
    equations { U 0.9; }
    fields { p 1; }
}
""" % self.tolerance)
        write(os.path.join(d, 'system', 'decomposeParDict'),
              # Debian's OpenFOAM has no scotch (a dummy library): slabs
              # along x, the flow direction
              'numberOfSubdomains %d;\nmethod hierarchical;\n'
              'coeffs { n (%d 1 1); order xyz; }\n' % (self.ranks,
                                                         self.ranks))


def _rows(pattern):
    """Number rows of the function-object files matching @p pattern."""
    rows = []
    for path in sorted(glob.glob(pattern)):
        with open(path) as f:
            for line in f:
                if line.strip() and not line.startswith('#'):
                    rows.append(line.replace('(', ' ').replace(')', ' ')
                                .split())
    return rows


def force_history(directory):
    """[(iteration, x force in N)] as written every 10 iterations."""
    return [(int(float(r[0])), float(r[1])) for r in _rows(os.path.join(
        directory, 'postProcessing', 'forces', '*', 'force.dat'))]


def plane_pressure_history(directory, i, rho):
    """[(iteration, area-averaged pressure in Pa)] on cutting plane @p i."""
    return [(int(float(r[0])), rho * float(r[1])) for r in _rows(
        os.path.join(directory, 'postProcessing', 'plane%d' % i, '*',
                     'surfaceFieldValue.dat'))]


def permeability_history(directory, planes, q, mu, rho):
    """[(iteration, K = q mu L / dp)] between the two cutting planes at
    @p planes, q the superficial velocity."""
    p0, p1 = (plane_pressure_history(directory, i, rho) for i in (0, 1))
    length = abs(planes[1] - planes[0])
    return [(n, q * mu * length / (a - b))
            for (n, a), (_, b) in zip(p0, p1) if a != b]


def mesh_cells(directory):
    """Cells of the mesh that snappyHexMesh wrote (its log's last count)."""
    cells = re.findall(r'cells:(\d+)', open(os.path.join(
        directory, 'log.snappyHexMesh')).read())
    return int(cells[-1]) if cells else 0


def iterations_to_settle(history, tolerance):
    """The first iteration after which a quantity's history [(iteration,
    value)] stays within @p tolerance of its last value."""
    last = history[-1][1]
    for i, (n, _) in enumerate(history):
        if all(abs(v - last) <= tolerance * abs(last) for _, v in history[i:]):
            return n
    return history[-1][0]
