# SPDX-License-Identifier: BSD-3-Clause
"""SchlierenImage's advanced device properties: DeviceName and Threads.

Run: pvpython test_device.py --plugin <Schlieren.so>

- DeviceName set to a name no OpenCL device has: with Backend OpenCL a clear error naming it, an
  empty output and no crash; with Backend Auto the CPU backend, with a warning naming it in the
  `warnings` field data, and the image of Backend CPU bit for bit (the same physics source and the
  same photons).
- Threads 1 and 2 on Backend CPU: the same image bit for bit (each ray is traced alone and the
  film sums are added in ray order whatever thread traced the ray), and the `device` field data
  says how many threads ran.
- Threads -5 and 100000: refused naming Threads, the value and the range 0..4096.
- Threads 1000 and 4096 under an address-space limit that leaves room for only a few thread
  stacks: Threads 1's image, no abort (threads the system refuses are not needed).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import numpy as np
from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager as sm

import schlieren_testing as st

st.load_plugin(globals())
T = st.Checker("test_device")

NAME = "no-such-device-7q"
scene = RefractiveScene(Scene="GaussianSphere", Dimensions=[32, 32, 32], Amplitude=1e-4, Width=0.3)
common = dict(Resolution=[32, 32], Passes=2, Cutoff="KnifeEdge", CutoffScale=st.KNIFE_SCALE)


def trace(**kw):
    args = dict(common)
    args.update(kw)
    image = SchlierenImage(Input=scene, **args)
    with st.CapturedOutput() as out:
        data = sm.Fetch(image)
    Delete(image)
    if data is None or data.GetNumberOfPoints() == 0:
        return None, None, {}, out.text
    _, _, I, D, F = st.image_arrays(data)
    return I, D, F, out.text


# 1. Backend OpenCL, a device name no device has: an error that names it, no image
I, _, _, text = trace(Backend="OpenCL", DeviceName=NAME)
T.check(I is None, "OpenCL, DeviceName %r: no image" % NAME)
T.check("ERROR" in text and NAME in text,
        "OpenCL, DeviceName %r: an error naming it (got: %s)" % (NAME, text.strip()[:400]))

# 2. Backend Auto, the same name: the CPU backend with a warning naming it
I_auto, D_auto, F, text = trace(Backend="Auto", DeviceName=NAME)
T.check(I_auto is not None and "ERROR" not in text, "Auto, DeviceName %r: an image, no error" % NAME)
T.check(F.get("backend") == "CPU", "Auto, DeviceName %r: traced on the CPU (backend %r)"
        % (NAME, F.get("backend")))
T.check(NAME in F.get("warnings", ""), "Auto, DeviceName %r: the warnings field names it (got %r)"
        % (NAME, F.get("warnings", "")[:300]))
I_cpu, D_cpu, _, _ = trace(Backend="CPU")
T.check(I_auto is not None and np.array_equal(I_auto, I_cpu) and np.array_equal(D_auto, D_cpu),
        "Auto's fallback image equals Backend CPU's bit for bit")

# 3. Threads 1 and 2 on the CPU: the same image; the device field says how many ran
I1, D1, F1, _ = trace(Backend="CPU", Threads=1)
I2, D2, F2, _ = trace(Backend="CPU", Threads=2)
T.check(I1 is not None and I2 is not None and np.array_equal(I1, I2) and np.array_equal(D1, D2),
        "Threads 1 and 2: the same image bit for bit")
T.check("(1 thread" in F1.get("device", ""), "Threads 1: device %r" % F1.get("device"))
T.check("(2 threads" in F2.get("device", ""), "Threads 2: device %r" % F2.get("device"))
T.check(I1 is not None and float(np.ptp(I1)) > 0.1, "the image is not flat (range %.3g)"
        % (float(np.ptp(I1)) if I1 is not None else 0.0))

# 4. Threads outside 0..4096: an error naming Threads, the value and the range, no image
for bad in (-5, 100000):
    I, _, _, text = trace(Backend="CPU", Threads=bad)
    T.check(I is None and "Threads is %d" % bad in text and "[0, 4096]" in text,
            "Threads %d: refused naming the property, value and range (got: %s)"
            % (bad, text.strip()[:300]))

# 5. Threads 1000 and 4096 (inside the range) under an address-space limit too small for the
# stacks of that many threads: the engine starts at most 16 per hardware thread and, where the
# system refuses one, traces on those it has. The image is Threads 1's, no abort, no error.
import resource  # noqa: E402


def vm_size():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) * 1024
    return 0


soft, hard = resource.getrlimit(resource.RLIMIT_AS)
# room for the film and a handful of thread stacks (8 MiB each by default), not for 16 per core
limit = vm_size() + (96 << 20)
if hard == resource.RLIM_INFINITY or hard >= limit:
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    try:
        for many in (1000, 4096):
            I, D, F, text = trace(Backend="CPU", Threads=many)
            T.check(I is not None and "ERROR" not in text and np.array_equal(I, I1)
                    and np.array_equal(D, D1),
                    "Threads %d under a %d MiB address-space margin: Threads 1's image (device %r, %s)"
                    % (many, 96, F.get("device"), text.strip()[:300]))
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
else:
    print("test_device: the hard address-space limit is below the test's; part 5 skipped")
sys.exit(T.finish())
