"""Draw the speed-versus-accuracy chart from SchlierenAccuracyChart's CSV.

    /usr/bin/python3 Testing/Benchmarks/accuracy_chart.py build/accuracy_chart.csv docs/accuracy_chart.png

(SchlierenAccuracyChart writes build/accuracy_chart.csv, or the file its --csv names;
scripts/accuracy_chart.sh passes out/accuracy_chart.csv.)

One panel per known-answer scene: time per pass (x) against the error of the traced deflection
relative to the answer's largest deflection (y), one colour per integrator, one marker per octree
tolerance (diamonds: Reconstruction Cubic, octree off); settings flagged for stepping over
structure are hollow; the Pareto front (no other
setting both faster and more accurate) is the black line. Auto's line (red, dashed): Integrator
and Reconstruction Auto at tolerances from 1e-1 to 1e-5 of the largest deflection, its choice at
each (the rows "Auto line"), each point labelled with its tolerance: a point whose error is below
its label met its tolerance against the known answer.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"Straight": "tab:grey", "Euler": "tab:blue", "Verlet": "tab:cyan", "Midpoint": "tab:orange", "RK4": "tab:green", "Auto": "tab:red", "Auto 1e-3": "tab:purple"}
AUTO_LINE = "Auto line"
MARKERS = {0.0: "o", 0.0001: "s", 0.01: "^"}


def main(src, dst):
    rows = defaultdict(list)
    with open(src) as f:
        for r in csv.DictReader(f):
            rows[r["scene"]].append(r)
    scenes = list(rows)
    fig, axes = plt.subplots(2, (len(scenes) + 1) // 2, figsize=(12, 9))
    for ax, scene in zip(axes.flat, scenes):
        pts, line = [], []
        for r in rows[scene]:
            if r["method"] == AUTO_LINE:
                line.append((float(r["tolerance"]), float(r["ms_per_pass"]),
                             max(float(r["relative_error"]), 1e-7)))
                continue
            ms, err = float(r["ms_per_pass"]), max(float(r["relative_error"]), 1e-7)
            tol = float(r["octree_tolerance"])
            flagged = r["flagged"] == "1"
            c = COLOURS[r["method"]]
            cubic = r.get("reconstruction", "Trilinear") == "Cubic"
            auto = r["method"].startswith("Auto")
            ax.scatter(ms, err, marker="*" if auto else "D" if cubic else MARKERS.get(tol, "x"), s=90 if auto else 36,
                       facecolors="none" if flagged else c, edgecolors=c)
            pts.append((ms, err, r))
        pts.sort(key=lambda p: p[0])
        front, best = [], float("inf")
        for ms, err, r in pts:
            if err < best:
                best = err
                front.append((ms, err))
        ax.plot([p[0] for p in front], [p[1] for p in front], "k-", lw=1, label="Pareto front")
        if line:
            line.sort(reverse=True)  # loosest tolerance first
            ax.plot([p[1] for p in line], [p[2] for p in line], "--", color="tab:red", lw=1.5, marker="*", ms=8)
            for tol, ms, err in line:
                ax.annotate("%g" % tol, (ms, err), textcoords="offset points", xytext=(4, -10), fontsize=7,
                            color="tab:red")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(top=2, bottom=1e-7)
        ax.set_title(scene)
        ax.set_xlabel("ms per pass")
        ax.set_ylabel("error / largest deflection")
        ax.grid(True, which="both", alpha=0.3)
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=m) for m, c in COLOURS.items()
               if not m.startswith("Auto")]
    handles += [plt.Line2D([], [], color="k", marker=mk, ls="", mfc="none",
                           label="octree off" if t == 0 else "octree %g of range" % t)
                for t, mk in MARKERS.items()]
    handles.append(plt.Line2D([], [], color="k", marker="D", ls="", mfc="none", label="Reconstruction Cubic"))
    handles.append(plt.Line2D([], [], color="tab:red", marker="*", ls="", ms=10, label="Auto, default tolerance"))
    handles.append(plt.Line2D([], [], color="tab:purple", marker="*", ls="", ms=10, label="Auto, 1e-3 of max deflection"))
    handles.append(plt.Line2D([], [], color="k", label="Pareto front"))
    handles.append(plt.Line2D([], [], color="tab:red", ls="--", marker="*", label="Auto at tolerances 1e-1 to 1e-5 of max deflection (labelled)"))
    fig.legend(handles=handles, loc="lower center", ncol=4)
    fig.suptitle("Schlieren: time per pass against error (hollow: flagged as stepping over structure)")
    fig.tight_layout(rect=(0, 0.08, 1, 0.96))
    fig.savefig(dst, dpi=90)
    print("wrote", dst)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
