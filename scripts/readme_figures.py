#!/usr/bin/env python3
"""The figures a README picture shows, as JSON (scripts/readme_pictures.sh).

  readme_figures.py ROOT RUN_DIR    docs/img/report.json of the run in RUN_DIR
  readme_figures.py --frame ROOT    docs/img/frame.json
  readme_figures.py --figures RUN_DIR
                                    the figures alone (tests/report/test_readme_pictures.sh)

Figures are rounded to the 3 significant digits the report shows, so a run
that the picture still shows gives the same JSON.
"""
import hashlib
import json
import math
import pathlib
import re
import sys

SCENARIO = "scenarios/main.yaml"
ROBOT = "models/gpm2002.yaml"


def sha256(path):
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


def round3(v):
    """v to 3 significant digits (None stays None)."""
    if v is None or v == 0 or not math.isfinite(v):
        return v
    return float(f"{v:.3g}")


def figures(run_dir):
    """The figures of the report's first screen, from the run's summary.json and report.md."""
    run = pathlib.Path(run_dir)
    s = json.loads((run / "summary.json").read_text())
    acc = s["accuracy"]
    worst = max((abs(p["estimated"] - p["actual"]) / p["crb"] for p in s["parameters"].values() if p["crb"]),
                default=None)
    mt = s["model_test"]
    md = (run / "report.md").read_text()
    lead = re.search(r"^\*\*(.*)\*\*$", md, re.M)
    expectations = re.search(r"Verdict: [^:]*: (?:all )?(\d+)", md)
    return {
        "verdict": s["verdict"],
        "nominal_static_rms_um": round3(acc["nominal"]["static_rms_um"]),
        "calibrated_static_rms_um": round3(acc["calibrated"]["static_rms_um"]),
        "actual_static_rms_um": round3(acc["actual"]["static_rms_um"]),
        "calibrated_path_rms_um": round3(acc["calibrated"]["path_rms_um"]),
        "floor_ratio": round3(acc["calibrated"]["static_rms_um"] / acc["actual"]["static_rms_um"]),
        "robot_time_s": round3(s["robot_time_s"]),
        "worst_crb_ratio": round3(worst),
        "model_test_chi2_per_dof": round3(mt["chi2"] / mt["dof"]) if mt else None,
        "model_test_passed": mt["passed"] if mt else None,
        "positioning_error_per_stated_sigma": round3(s["positioning_um"]["normalised_rms"])
        if s["positioning_um"] else None,
        "expectations": int(expectations.group(1)) if expectations else None,
        "lead": lead.group(1) if lead else None,
    }


def main(argv):
    if argv[:1] == ["--figures"]:
        print(json.dumps(figures(argv[1]), indent=2, ensure_ascii=False))
        return 0
    if argv[:1] == ["--frame"]:
        root = pathlib.Path(argv[1])
        out = {"picture": "docs/img/frame.png", "picture_sha256": sha256(root / "docs/img/frame.png"),
               "source": SCENARIO, "source_sha256": sha256(root / SCENARIO), "robot_sha256": sha256(root / ROBOT)}
        print(json.dumps(out, indent=2, ensure_ascii=False))
        return 0
    root, run = pathlib.Path(argv[0]), argv[1]
    out = {"picture": "docs/img/report.png", "picture_sha256": sha256(root / "docs/img/report.png"),
           "source": SCENARIO, "source_sha256": sha256(root / SCENARIO), "robot_sha256": sha256(root / ROBOT),
           "figures": figures(run)}
    print(json.dumps(out, indent=2, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
