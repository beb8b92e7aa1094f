"""The README's GUI screenshot: the ParaView GUI with the blunt fin's resampled volume (3D view) and
its knife-edge schlieren image side by side, saved from the GUI's own layout.

    SCHLIEREN_PLUGIN=$(echo build/lib/paraview-*/plugins/Schlieren/Schlieren.so) SCHLIEREN_DATA=../shared/data \
    SCHLIEREN_SCREENSHOT=docs/gui_layout.png Testing/with_xvfb.sh paraview --dr --script=Examples/gui_layout.py
"""
import os

from paraview.simple import *  # noqa: F401,F403

LoadPlugin(os.environ["SCHLIEREN_PLUGIN"], remote=False, ns=globals())
data = os.environ.get("SCHLIEREN_DATA", "../shared/data")
reader = PLOT3DReader(registrationName="bluntfin", FileName=data + "/bluntfinxyz.bin", QFileName=[data + "/bluntfinq.bin"])
index = RefractiveIndex(registrationName="RefractiveIndex1", Input=reader, Model="GladstoneDale", Gas="Air", DensityReference=1.2,
                        UseSamplingBounds=1, SamplingBounds=[-2.5, 7.5, 0.0, 5.0, 0.0, 5.7], AutomaticDimension=128, AmbientMode="Extend")
index.InputArray = ["POINTS", "Density"]
image = SchlierenImage(registrationName="SchlierenImage1", Input=index, Cutoff="KnifeEdge", CutoffScale=40.0,
                       Resolution=[640, 320], Passes=16, Filter="Gaussian", FilterWidth=0.7, ViewDirection=[0, 0, -1], ViewUp=[0, 1, 0],
                       OpenImageView=0)  # this script lays the views out itself
layout = GetLayout()
rv3 = GetActiveViewOrCreate("RenderView")
d = Show(index, rv3)
d.Representation = "Outline"
ColorBy(d, None)
rv3.ViewSize = [480, 480]
ResetCamera(rv3)
cam = rv3.GetActiveCamera()
cam.Elevation(35)
cam.Azimuth(-30)
cam.OrthogonalizeViewUp()
ResetCamera(rv3)

layout.SplitHorizontal(0, 0.4)
rv2 = CreateView("RenderView")
layout.AssignView(2, rv2)
di = Show(image, rv2)
ColorBy(di, ("POINTS", "intensity"))
lut = GetColorTransferFunction("intensity")
lut.ApplyPreset("Grayscale", True)
lut.RescaleTransferFunction(0.0, 1.0)
rv2.InteractionMode = "2D"

rv2.OrientationAxesVisibility = 0
ResetCamera(rv2)
SetActiveSource(image)
SetActiveView(rv2)
Render(rv3)
Render(rv2)
SaveScreenshot(os.environ.get("SCHLIEREN_SCREENSHOT", "gui_layout.png"), layout, SaveAllViews=1,
               ImageResolution=[1200, 480])
os._exit(0)  # the GUI would wait for a user
