"""Follow a render view's camera with a SchlierenImage: rotate the volume, the schlieren image
re-traces along the new line of sight, coarse while the camera moves, refined pass after pass when
it stops (the paper's section 7).

Installed beside the Schlieren plugin, which puts its folder on sys.path when loaded: after
LoadPlugin, in pvpython, pvbatch or the GUI's Python shell,

    import schlieren_view
    follower = schlieren_view.follow_camera(view, image, target_passes=32)

`view` is a render view showing the volume (the camera the user turns), `image` a SchlierenImage.
Every change of the camera sets the image's ViewDirection and ViewUp from it and drops it to
`interactive_passes` passes (a blurry image at once); `refine()` then adds passes up to
`target_passes`; the filter traces only the passes it does not have yet (progressive refinement),
and a camera change in between starts over. Where an event loop runs (the GUI), a repeating timer
of the view's interactor calls `refine()` while the camera rests; in a script, call it yourself.

Why this route (and not a representation that traces at render time): it is a client-side driver
of an ordinary filter, so the same image, properties and arrays serve the GUI, pvpython, pvbatch
and pvserver (the filter runs where the data is; only the two camera vectors travel), and the
refinement reuses the filter's own cache. Its limit: on a remote server each step is a round trip
of the image, and the GUI is driven by the view's interactor timer rather than by ParaView's
render-time LOD machinery.
"""
import math


def _unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v] if n > 0 else list(v)


class CameraFollower:
    """Keeps a SchlierenImage's line of sight on a render view's camera (see the module's text)."""

    def __init__(self, view, image, interactive_passes=1, target_passes=None, step=None):
        self.view = view
        self.image = image
        self.interactive_passes = max(1, int(interactive_passes))
        self.target_passes = int(target_passes) if target_passes else max(1, int(image.Passes))
        self.step = int(step) if step else max(1, self.target_passes // 4)
        self.camera = view.GetActiveCamera()
        self.moved = 0  # camera changes seen
        self._tags = [self.camera.AddObserver("ModifiedEvent", self._on_camera)]
        self._timer = None
        self.also_render = []  # views besides `view` to render after each refinement
        self.alive = None  # a callable: False once the image is gone (then the follower stops)
        self.sync()

    # the camera's line of sight, as the filter's properties
    def camera_vectors(self):
        pos, focal = self.camera.GetPosition(), self.camera.GetFocalPoint()
        direction = _unit([f - p for f, p in zip(focal, pos)])
        return direction, list(self.camera.GetViewUp())

    def sync(self):
        """Sets ViewDirection/ViewUp from the camera and drops to the interactive passes."""
        direction, up = self.camera_vectors()
        self.image.ViewDirection = direction
        self.image.ViewUp = up
        self.image.Passes = self.interactive_passes

    def _gone(self):
        if self.alive is not None and not self.alive():
            self.stop()
            return True
        return False

    def _on_camera(self, caller, event):
        if self._gone():
            return
        direction, up = self.camera_vectors()
        current = list(self.image.ViewDirection), list(self.image.ViewUp)
        if all(abs(a - b) < 1e-12 for a, b in zip(current[0] + current[1], direction + up)):
            return  # a camera change that is not a rotation (zoom, pan): the image stays
        self.moved += 1
        self.sync()  # a new interaction cancels the refinement in progress

    def refine(self):
        """Adds up to `step` passes (towards the target) and updates the image; returns True while
        more are to come."""
        passes = int(self.image.Passes)
        if passes >= self.target_passes:
            return False
        self.image.Passes = min(self.target_passes, passes + self.step)
        self.image.UpdatePipeline()
        return int(self.image.Passes) < self.target_passes

    def start_timer(self, interval_ms=200):
        """Where the view's interactor runs an event loop (the GUI): refine while the camera rests."""
        interactor = self.view.GetRenderWindow().GetInteractor()
        if interactor is None:
            return False
        self._timer = interactor.CreateRepeatingTimer(interval_ms)

        def on_timer(caller, event):
            if self._gone():
                return
            before = int(self.image.Passes)
            self.refine()
            if int(self.image.Passes) != before:  # passes added, the last chunk's too
                self.view.StillRender()
                for view in self.also_render:  # other views showing the image (the Python plugin's)
                    view.StillRender()

        self._tags.append(interactor.AddObserver("TimerEvent", on_timer))
        return True

    def stop(self):
        """Stops following the camera."""
        if not self._tags:
            return
        self.camera.RemoveObserver(self._tags[0])
        if self._timer is not None:
            interactor = self.view.GetRenderWindow().GetInteractor()
            interactor.DestroyTimer(self._timer)
            for tag in self._tags[1:]:
                interactor.RemoveObserver(tag)
        self._tags = []


def follow_camera(view, image, interactive_passes=1, target_passes=None, step=None, timer=True):
    """Makes `image` follow `view`'s camera; returns the CameraFollower (keep a reference)."""
    follower = CameraFollower(view, image, interactive_passes, target_passes, step)
    if timer:
        follower.start_timer()
    return follower


def film_array(data, name="intensity"):
    """A SchlierenImage output's point array as a numpy array of shape (ny, nx) or (ny, nx, c)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    nx, ny, _ = data.GetDimensions()
    a = data.GetPointData().GetArray(name)
    if a is None:
        raise KeyError("the image has no point array %r" % name)
    c = a.GetNumberOfComponents()
    return vtk_to_numpy(a).reshape((ny, nx) + ((c,) if c > 1 else ()))


def write_png(values, path):
    """Writes a (ny, nx) array in [0, 1] as 8-bit grey, or (ny, nx, 3) as colour, row 0 at the
    bottom (as the film's); values outside [0, 1] are clipped."""
    import os

    import numpy as np
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter

    values = np.clip(np.asarray(values, dtype=float), 0.0, 1.0)
    ny, nx = values.shape[:2]
    comps = 1 if values.ndim == 2 else values.shape[2]
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    image.GetPointData().SetScalars(
        numpy_to_vtk((255.0 * values + 0.5).astype(np.uint8).reshape(ny * nx, comps), deep=1))
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    writer = vtkPNGWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()
