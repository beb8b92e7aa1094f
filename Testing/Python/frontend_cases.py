# SPDX-License-Identifier: BSD-3-Clause
"""The cases on which the Python front end (Python/schlieren) must give the C++ plugin's image bit
for bit: what both sides build and trace. Imported by frontend_reference.py (pvpython, the C++
plugin) and test_frontend.py (a venv with PyPI's vtk and the package); no ParaView or VTK here."""

# RefractiveScene properties of the scene cases (the blunt fin is RefractiveIndex's grid of the
# PLOT3D result, written by the reference run as a .vti that both sides trace)
SCENES = {
    "gaussian_sphere": dict(Scene="GaussianSphere", Dimensions=[48, 48, 48],
                            Bounds=[-1.0, 1.0, -1.0, 1.0, -1.0, 1.0], Amplitude=1e-4, Width=0.25),
    "solid_sphere": dict(Scene="GaussianSphere", Dimensions=[48, 40, 44],
                         Bounds=[-1.0, 1.0, -0.8, 0.9, -1.0, 1.0], Amplitude=2e-4, Width=0.4,
                         Body="Sphere", BodyRadius=0.3, BodyCenter=[0.1, 0.0, 0.0]),
    # the scene's density through RefractiveIndex and RefractionOctree (STAGES), traced with
    # the octree
    "indexed_sphere": dict(Scene="GaussianSphere", Dimensions=[40, 36, 32],
                           Bounds=[-1.0, 1.0, -0.9, 0.9, -0.8, 0.8], Amplitude=1e-4, Width=0.3),
}
# small scenes for the cases that set every SchlierenImage property away from its default
# (SETTINGS_CASES): the property -> engine setting mapping of either front end cannot drift
# unnoticed
for _case in ("settings_color", "settings_bench", "settings_bos", "settings_fringes", "settings_camera",
              "settings_stop"):
    SCENES[_case] = dict(Scene="GaussianSphere", Dimensions=[28, 26, 24],
                         Bounds=[-1.0, 1.0, -0.9, 0.9, -0.8, 0.8], Amplitude=2e-4, Width=0.35,
                         Body="Sphere" if _case == "settings_bos" else "None", BodyRadius=0.2)

SETTINGS_NOT_VARIED = {"Backend", "DeviceName"}

# the filters between a scene and SchlierenImage, in order (proxy name, properties)
STAGES = {
    "indexed_sphere": [("RefractiveIndex", dict(Model="GladstoneDale",
                                                InputArray=["POINTS", "density"],
                                                DensityReference=2.0)),
                       ("RefractionOctree", dict(Tolerance=1e-6, MaxLevel=5))],
}

# SchlierenImage properties per case (a few away from the defaults, so that they are all passed)
IMAGES = {
    "gaussian_sphere": dict(Cutoff="KnifeEdge", KnifeAngle=30.0, Resolution=[96, 80], Passes=2,
                            Integrator="RK4", StepSize=0.5, ViewDirection=[0.2, 0.1, -1.0],
                            Source="Slit"),  # a finite source: the bench_* field data
    "solid_sphere": dict(Cutoff="Shadowgraph", FilmDistance=0.5, Resolution=[80, 80], Passes=2,
                         Seed=7),
    "indexed_sphere": dict(Cutoff="KnifeEdge", Resolution=[64, 56], Passes=1, UseOctree=1,
                           KnifeAngle=90.0),
    # every engine property of SchlierenImage away from its default in one of these (Backend is
    # the loop's; DeviceName stays empty: the device is the machine's one)
    "settings_color": dict(Cutoff="ColorFilter", CutoffScale=800.0, Integrator="Midpoint",
                           Reconstruction="Cubic", StepSize=0.7, EstimateError=1, KeepInvariant=1,
                           Filter="Gaussian", FilterWidth=1.5, RussianRoulette=1, Jitter=0,
                           Seed=11, Threads=2, Resolution=[40, 36], Passes=3,
                           ViewUp=[0.1, 1.0, 0.0], Tolerance=1e-5, UseOctree=0),
    "settings_bench": dict(Cutoff="KnifeEdge", Source="Disc", SourceSize=[2.0, 1.5],
                           CollimatorFocalLength=1.5, SchlierenFocalLength=2.5, KnifeCut=0.3,
                           BitDepth=10, SaturationWarning=0.05, KnifeAngle=45.0,
                           Resolution=[36, 36], Passes=2, TraceInPieces=0),
    "settings_bos": dict(Cutoff="BOS", BackgroundDistance=0.5, BackgroundPattern="Stripes",
                         BackgroundPeriod=3.0, FilmDistance=0.2, Resolution=[36, 32], Passes=2,
                         Filter="Cone", FilterWidth=2.0, JitterPattern="Random"),
    "settings_fringes": dict(Cutoff="Interferometry", Wavelength=532.0, ReferenceTilt=4.0,
                             Framing="Silhouette", WavelengthRange=[450.0, 650.0],
                             WavelengthBins=4, Dispersion="None",
                             Resolution=[36, 36], Passes=2, Integrator="Euler", StepSize=0.3),
    # a pinhole's image through a circular aperture in mm (the bench's closed-form stop)
    "settings_stop": dict(Cutoff="Circular", Source="Disc", SourceSize=[1.0, 1.0], StopDiameter=1.2,
                          Resolution=[36, 36], Passes=2),
    # a lens focused off the volume's centre: the aperture sampled over the passes
    "settings_camera": dict(Cutoff="KnifeEdge", Camera="Lens", CameraFocalLength=0.2, FNumber=2.8,
                            CameraDistance=1.5, FocusPlane=0.2, SourceGridDistance=3.0,
                            Resolution=[36, 36], Passes=3),
    "bluntfin": dict(Cutoff="KnifeEdge", Resolution=[96, 64], Passes=2, ViewDirection=[0, -1, 0],
                     ViewUp=[0, 0, 1], Integrator="Auto"),  # Auto's choice: the auto_* field data
}

BACKENDS = ["CPU", "OpenCL"]

# the arrays compared (those an image has)
ARRAYS = ["intensity", "deflection", "blocked", "rgb", "phase", "bos_displacement",
          "numerical_gradient"]

# NumericalSchlieren cases: the scene case whose output it takes, and its properties
NUMERICAL = {
    "numerical_line": ("solid_sphere", dict(Mode="LineOfSight", Gradient="KnifeComponent",
                                            KnifeAngle=30.0, Resolution=[64, 56],
                                            ViewDirection=[0.1, 0.0, -1.0])),
    "numerical_slice": ("gaussian_sphere", dict(Mode="Slice", Resolution=[48, 48],
                                                SliceOffset=0.1, DensityArray="density")),
}

# field data compared exactly (numbers and strings); timings and devices are not in the report
FIELDS = ["cutoff_scale", "photons", "passes", "samples", "failed_rays", "missed_rays",
          "landed_photons", "blocked_rays", "integrator", "reconstruction", "step_size", "backend"]


def field_data_list(fd):
    """Every array of an image's field data, in order: [name, "text" or "number", values], the
    numbers as repr() text (exact, NaN equal to NaN), the device's name left out (its place kept) so
    that lists written on another machine or PoCL compare too. The C++ filter writes its field data from the
    engine's report (schlieren::ImageReport) and the Python front end from the same report through
    the C interface: the two lists must be equal, names, order and values."""
    import re
    out = []
    for i in range(fd.GetNumberOfArrays()):
        a = fd.GetAbstractArray(i)
        n = a.GetNumberOfTuples() * a.GetNumberOfComponents()
        if a.IsA("vtkStringArray"):
            values = [a.GetValue(j) for j in range(n)]
            if a.GetName() == "auto_report":  # the one timing in the report: the pilot's ms
                values = [re.sub(r"rays, \d+ ms\)", "rays, ... ms)", v) for v in values]
            if a.GetName() == "device":  # the machine's, not the image's: PoCL names its CPU
                values = ["..."]         # device "pthread-<cpu>" in 3.1, "cpu-<cpu>" from 5.0 on
            out.append([a.GetName(), "text", values])
        else:
            out.append([a.GetName(), "number", [repr(float(a.GetValue(j))) for j in range(n)]])
    return out


# what of the C++ plugin the Python plugin leaves out, by name (Plugin/make_python_plugin.py
# leaves out the same): the tests diff the two plugins' property lists less these
PYTHON_PLUGIN_PROXIES_LEFT_OUT = set()
PYTHON_PLUGIN_LEFT_OUT = {
    # the C++ plugin's toolbar's (the Python plugin has FollowCamera and InteractivePasses)
    "SchlierenImage": {"InteractiveScale", "OpenImageView", "PassLimit"},
    "NumericalSchlieren": {"FollowCamera", "OpenImageView"},  # the C++ plugin's toolbar's
    "RefractiveScene": {"TimeSteps", "TimestepValues"},  # the time series ParaView animates
}

# RefractiveIndex's parity matrix: every property value class, each a case run through the C++
# plugin (frontend_reference.py), the Python plugin (test_python_plugin_parity.py, pvpython) and
# the Python front end in pip VTK (test_frontend.py), compared bit for bit (frontend_matrix.py):
# the index's grid, point arrays and field data, and SchlierenImage's film on it. A case is
# (input, RefractiveIndex properties, SchlierenImage properties beyond INDEX_IMAGE); the inputs are
# frontend_matrix.make_inputs' (bluntfin, disk: ../shared/data's; ladenburg, forward_step: the
# suite's solved OpenFOAM cases; each left out, said, where absent).
#   class                      case(s)
#   each model                 model_* (Passthrough, GladstoneDale, GladstoneDaleMixture by mixture
#                              fraction and by species, IdealGas by gas and by species, Ciddor with
#                              constants and with arrays, Automatic: a temperature and a pressure,
#                              an array named n)
#   Symmetry None              symmetry_none_curvilinear, unstructured_disk, image_blocks (and
#                              every model_*)
#   Symmetry Planar            symmetry_planar (2D image), symmetry_planar_unstructured,
#                              openfoam_forward_step (rhoCentralFoam's forwardStep at t = 2)
#   Symmetry Axisymmetric      symmetry_axisymmetric (a cone's r-z half plane about X)
#   a wedge, no axis typed     wedge_no_axis_typed (AxisFromWedge finds it), openfoam_wedge
#                              (LadenburgJet60psi's converged solution)
#   bodies from holes          body_from_holes (vtkValidPointMask's enclosed hole), body_solid_array
#   bodies from walls          body_from_walls (the blunt fin, BodyWallFaces 0 1 1 0 1 1)
#   the Body input (port 1)    body_surface (a sphere's surface on the Gaussian scene: INDEX_BODY)
#   SamplingBounds             sampling_bounds (a box past a curvilinear grid), body_from_walls
#   AmbientMode                sampling_bounds (Extend), ambient_median, ambient_value,
#                              bluntfin_ambient_value
#   AMR                        amr (two levels of a vtkOverlappingAMR, .vthb)
#   cell data only             cell_data_only (a tetrahedralized Wavelet's cells: converted to
#                              point data, noted)
#   not here yet               bodies beside walls from the velocity (branch
#                              issue47-index-engine): one line below when it comes
INDEX_OPTIONAL_INPUTS = {"bluntfin", "disk", "ladenburg", "forward_step"}  # left out where absent
# Symmetry (OpenFOAM's hexahedra one cell thick, the 2D images and meshes): both front ends sample
# the input at the points the engine's plan gives with the engine's cell sampler (its points mode,
# schlieren_sample_cells_at), so every case is bit for bit in every VTK (with VTK's probe, as
# before, pip vtk 9.7.2 found other cells than 9.2: the forward step's n - 1 differed at 606 of
# 9216 points, by up to 1.5e-6; Testing/Benchmarks/symmetric_sampling.py compares the two samplers)
# The cases with a Body input (port 1): the case's name and the input's (a closed surface)
INDEX_BODY = {"body_surface": "sphere"}
_GD = dict(Model="GladstoneDale", InputArray="density")
_BOX = [-1.2, 1.2, -1.1, 1.1, -0.9, 0.9]  # past the sheared grid's bounds on every side
_FIN = dict(Model="GladstoneDale", Gas="Air", DensityReference=1.2, InputArray="Density",
            AutomaticDimension=36, UseSamplingBounds=1,
            SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7])
_FIN_VIEW = dict(ViewDirection=[0, -1, 0], ViewUp=[0, 0, 1])
INDEX_IMAGE = dict(Backend="CPU", Resolution=[40, 32], Passes=1, ViewDirection=[0.1, 0.2, -1.0],
                   ViewUp=[0, 1, 0])
INDEX = {
    "model_passthrough": ("scene", dict(Model="Passthrough", InputArray="n_minus_1"), {}),
    "model_gladstone_dale": ("fields", dict(_GD, Gas="He", DensityReference=1.1), {}),
    "model_mixture_fraction": ("fields", dict(
        _GD, Model="GladstoneDaleMixture", MixtureComposition="MixtureFraction",
        MixtureFractionArray="mix", MixtureGas0="Air", MixtureGas1="He"), {}),
    "model_mixture_species": ("fields", dict(
        _GD, Model="GladstoneDaleMixture", MixtureComposition="Species", NumberOfSpecies=2,
        SpeciesGases=[6, 8, 1, 5], Species1Array="Y1", Species2Array="Y2", BalanceGas="N2"), {}),
    "model_ideal_gas": ("fields", dict(Model="IdealGas", Gas="CO2", TemperatureArray="T",
                                       PressureArray="p", PressureUnit="kPa"), {}),
    "model_ideal_gas_species": ("fields", dict(
        Model="IdealGas", IdealGasComposition="Species", NumberOfSpecies=2,
        SpeciesGases=[-1, 8, 1, 5], SpeciesGladstoneDale=[3e-4, 2.2e-4, 2e-4, 2e-4],
        SpeciesMolarMass=[0.04, 0.03, 0.004, 0.044], Species1Array="Y1", Species2Array="Y2",
        TemperatureArray="T", PressureArray="p", PressureUnit="kPa", TemperatureReference=1.1),
        {}),
    "model_ciddor": ("fields", dict(Model="Ciddor", TemperatureArray="T", PressureArray="p",
                                    PressureUnit="kPa", Humidity=0.4, CO2=500.0,
                                    Wavelength=550.0), {}),
    "model_ciddor_arrays": ("fields", dict(
        Model="Ciddor", TemperatureArray="T", PressureArray="p", PressureUnit="kPa",
        HumidityFromArray=1, HumidityArray="rh", CO2FromArray=1, CO2Array="co2"), {}),
    "model_automatic_ideal_gas": ("tp", dict(Model="Automatic", PressureUnit="kPa", Gas="Ar"), {}),
    "model_automatic_n": ("n", dict(Model="Automatic"), {}),
    "symmetry_none_curvilinear": ("sheared", dict(_GD, AutomaticDimension=28), {}),
    "symmetry_planar": ("plane", dict(_GD, Symmetry="Planar", Span=0.6),
                        dict(ViewDirection=[0, 0, -1])),
    "symmetry_planar_unstructured": ("plane_unstructured", dict(
        _GD, Symmetry="Planar", Span=0.6, AutomaticDimension=32), dict(ViewDirection=[0, 0, -1])),
    "symmetry_axisymmetric": ("cone", dict(_GD, Symmetry="Axisymmetric", SymmetryAxis="X",
                                           AutomaticDimension=32), dict(ViewDirection=[0, 0, -1])),
    "wedge_no_axis_typed": ("wedge", dict(_GD, Symmetry="Axisymmetric", AutomaticDimension=28),
                            dict(ViewDirection=[1, 0, 0])),
    "body_from_holes": ("masked", dict(Model="Passthrough", InputArray="n_minus_1",
                                       BodyFromGrid=1), {}),
    "body_solid_array": ("fields", dict(_GD, SolidArray="blk"), {}),
    "body_surface": ("scene", dict(Model="Passthrough", InputArray="n_minus_1"), {}),
    "sampling_bounds": ("sheared", dict(_GD, AutomaticDimension=28, UseSamplingBounds=1,
                                        SamplingBounds=_BOX), {}),
    "ambient_median": ("sheared", dict(_GD, AutomaticDimension=28, UseSamplingBounds=1,
                                       SamplingBounds=_BOX, AmbientMode="DomainEdgeMedian"), {}),
    "ambient_value": ("sheared", dict(_GD, AutomaticDimension=28, UseSamplingBounds=1,
                                      SamplingBounds=_BOX, AmbientMode="Value",
                                      AmbientValue=2.5e-4), {}),
    "body_from_walls": ("bluntfin", dict(_FIN, BodyFromGrid=1, BodyWallFaces=[0, 1, 1, 0, 1, 1]),
                        _FIN_VIEW),
    "bluntfin_ambient_value": ("bluntfin", dict(_FIN, BodyFromGrid=0, AmbientMode="Value",
                                                AmbientValue=2.5e-4), _FIN_VIEW),
    "openfoam_wedge": ("ladenburg", dict(Model="Automatic", Symmetry="Axisymmetric",
                                          SamplingDimensions=[64, 24, 24]),
                       dict(ViewDirection=[0, 0, -1])),
    "openfoam_forward_step": ("forward_step", dict(Model="Automatic", Symmetry="Planar", Span=0.1,
                                                   SamplingDimensions=[96, 32, 3]),
                              dict(ViewDirection=[0, 0, -1])),
    # AMR (frontend_matrix._amr: the scene's density on two levels of a vtkOverlappingAMR, written
    # as .vthb, read back with every level): both front ends read it into the engine's AMR
    # sampler (schlieren_amr_sample), the grid at the finest level's spacing (47 x 39 x 31 points)
    "amr": ("amr", dict(_GD, AutomaticDimension=32), {}),
    # blocks of images (the scene's halves in x, sharing a plane): the engine's cell sampler on
    # their voxels in both front ends (the probe's before)
    "image_blocks": ("image_blocks", dict(_GD, AutomaticDimension=28), {}),
    # a field given as cell data only (a tetrahedralized Wavelet, density = RTData / 200 on its
    # cells): both front ends turn the arrays the model reads into point data first
    # (vtkCellDataToPointData, the engine's rule CellOnlyFields) and note it in index_notes
    "cell_data_only": ("cells_only", dict(_GD, AutomaticDimension=20), {}),
    "unstructured_disk": ("disk", dict(Model="GladstoneDale", InputArray="Temp",
                                       DensityReference=1e-3, AutomaticDimension=28),
                          dict(ViewDirection=[1, 0, 0], ViewUp=[0, 0, 1])),
}
