"""Time per frame of an animation played twice: the first play resamples and packs every frame
(what every play cost before the per-time-step caches), the second takes both from the caches.

    pvpython Testing/Benchmarks/time_series.py --plugin build/lib/paraview-*/plugins/Schlieren/Schlieren.so \
        [--frames 6] [--scene 48] [--grid 96] [--resolution 256]

The series: RefractiveScene BlastWave (scene^3 points) made an unstructured grid (AppendDatasets)
and resampled by RefractiveIndex onto grid^3 points, traced by SchlierenImage (Shadowgraph,
resolution^2, 1 pass). Prints a table (seconds per frame: mean and largest) and what the field data
says was computed.
"""
import argparse
import os
import time

from paraview.simple import *  # noqa: F401,F403


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--plugin", required=True)
    ap.add_argument("--frames", type=int, default=6)
    ap.add_argument("--scene", type=int, default=48)
    ap.add_argument("--grid", type=int, default=96)
    ap.add_argument("--resolution", type=int, default=256)
    a = ap.parse_args()
    LoadPlugin(a.plugin, remote=False, ns=globals())
    scene = RefractiveScene(Scene="BlastWave", Dimensions=[a.scene] * 3, Bounds=[-1, 1] * 3,
                            Radius=0.7, Width=0.05, Time=1.0, TimeSteps=a.frames)
    grid = AppendDatasets(Input=scene)
    index = RefractiveIndex(Input=grid, SamplingDimensions=[a.grid] * 3)
    image = SchlierenImage(Input=index, Resolution=[a.resolution] * 2, Passes=1,
                           Cutoff="Shadowgraph", FilmDistance=1.0)
    scene.UpdatePipelineInformation()

    def field(proxy, name):
        fd = proxy.GetClientSideObject().GetOutputDataObject(0).GetFieldData()
        arr = fd.GetAbstractArray(name)
        return arr.GetVariantValue(0).ToString() if arr is not None else "-"

    rows = []
    for play in ("first play (no cache: resample + pack + trace)", "second play (cached: trace only)"):
        times = []
        for t in scene.TimestepValues:
            t0 = time.perf_counter()
            image.UpdatePipeline(t)
            times.append(time.perf_counter() - t0)
        rows.append((play, sum(times) / len(times), max(times), field(index, "index_computed"),
                     field(image, "volumes_packed"), field(image, "volume_from")))
    load = os.getloadavg()
    print("BlastWave %d^3 as an unstructured grid, %d frames, resampled to %d^3, film %d^2; "
          "load %.1f %.1f %.1f (shared machine)" % (a.scene, a.frames, a.grid, a.resolution, *load))
    print("cache budget (RefractiveIndex): %s bytes; held: %s bytes"
          % (field(index, "index_cache_budget"), field(index, "index_cache_bytes")))
    print("| play | s/frame (mean) | s/frame (max) | resamples so far | packs so far | last volume from |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %.3f | %.3f | %s | %s | %s |" % r)
    print("speed-up of the second play: %.1fx" % (rows[0][1] / rows[1][1]))


if __name__ == "__main__":
    main()
