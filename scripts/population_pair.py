"""Table cells "before -> after" of two `gpm study population` results of the
same robots (their population.json), for the studies that compare two
versions of the procedure (scripts/study_force_sign.sh, scripts/study_alternating_preload.sh,
scripts/study_friction_balance.sh, scripts/study_sample_weights.sh,
scripts/study_positioning_design.sh, scripts/study_cogging.sh) or of the twin
(scripts/study_friction_timeconst.sh),
and the table written into a document between its markers (those and
scripts/study_effect_budget.sh)."""
import json
import re
import statistics

# The table's names of the kinds of robot (kind_effects in scripts/effects_beyond_basic.sh).
KIND_LABEL = {'basic': 'the basic set', 'randomized': 'every effect drawn', 'preset': 'the `realistic` preset',
              'backlash': 'the basic set and backlash',
              'te_joint': "the basic set and the reducer's error once per joint revolution",
              'cogging': "the basic set and the motors' cogging"}


def load_pair(out, kind, before, after):
    """The population.json of DIR/KIND_BEFORE and DIR/KIND_AFTER."""
    return tuple(json.load(open(f"{out}/{kind}_{x}/population.json")) for x in (before, after))


def positioning_by_seed(p):
    """Each calibrated robot's positioning RMS (um) of population p, by seed."""
    return {r["seed"]: r["positioning_um"]["rms"] for r in p["robots"] if r["failure"] is None}


def before_after(a, b):
    """Cells of summaries a -> b: positioning median and worst (um), share within 3
    sigma, worst parameter (sigma), error / stated 1-sigma, model test passes,
    and the robots whose positioning got better / worse."""
    sa, sb = a["summary"], b["summary"]
    ra, rb = positioning_by_seed(a), positioning_by_seed(b)
    better = sum(1 for s in ra if s in rb and rb[s] < ra[s])
    worse = sum(1 for s in ra if s in rb and rb[s] > ra[s])
    return {
        "median": f"{sa['positioning_median_um']:.1f} -> {sb['positioning_median_um']:.1f}",
        "worst": f"{sa['positioning_max_um']:.0f} -> {sb['positioning_max_um']:.0f}",
        "within": f"{100 * sa['within_3_sigma_fraction']:.0f} -> {100 * sb['within_3_sigma_fraction']:.0f} %",
        "worst_sigma": f"{sa['worst_sigma_ratio']:.1f} -> {sb['worst_sigma_ratio']:.1f}",
        "per_sigma": f"{sa['normalised_positioning_median']:.2f} -> {sb['normalised_positioning_median']:.2f}",
        "passes": f"{100 * sa['model_test_pass_fraction']:.0f} -> {100 * sb['model_test_pass_fraction']:.0f} %",
        "better_worse": f"{better} / {worse}",
    }


def _chi2_median(p):
    """The median model-test chi2/dof of population p ("-" without a test)."""
    v = [r["model_test"]["chi2_per_dof"] for r in p["robots"] if r.get("model_test")]
    return f"{statistics.median(v):.3g}" if v else "-"


# Further columns of before_after_table: the least RMS the readings allow and the model test's chi2/dof.
BOUND_COLUMN = ("least RMS the readings allow, median (um)",
                lambda a, b: " -> ".join(f"{p['summary']['positioning_bound_median_um']:.1f}" for p in (a, b)))
MISFIT_COLUMN = ("model test chi2/dof, median", lambda a, b: f"{_chi2_median(a)} -> {_chi2_median(b)}")


def before_after_table(out, kinds, before, after, lead, extra=()):
    """The lines of the markdown table "before -> after" (before_after's cells)
    of DIR/KIND_BEFORE and DIR/KIND_AFTER for each kind, under the sentence lead;
    extra: further columns, each (header, cell(a, b) of the two population.json)."""
    lines = [lead, "",
             "| robots' effects | positioning RMS median (um) | worst robot (um) | parameters within 3 sigma | "
             "worst parameter (sigma) | error / stated 1-sigma (median) | model test passes | robots better / worse |"
             + "".join(f" {h} |" for h, _ in extra),
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |" + " ---: |" * len(extra)]
    for kind in kinds:
        a, b = load_pair(out, kind, before, after)
        c = before_after(a, b)
        lines.append(f"| {KIND_LABEL[kind]} | {c['median']} | {c['worst']} | {c['within']} | {c['worst_sigma']} | "
                     f"{c['per_sigma']} | {c['passes']} | {c['better_worse']} |" + "".join(f" {f(a, b)} |" for _, f in extra))
    return lines


def write_between_markers(doc, name, table):
    """Replaces what lies between the markers <!-- NAME:begin --> and <!-- NAME:end -->
    of file doc with table (nothing happens where the markers are missing)."""
    text = open(doc).read()
    begin, end = f"<!-- {name}:begin -->\n", f"<!-- {name}:end -->"
    if begin in text and end in text:
        text = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda m: begin + table + end, text, flags=re.S)
        open(doc, "w").write(text)


if __name__ == "__main__":
    # python3 scripts/population_pair.py OUT BEFORE AFTER NAME LEAD KIND...: the
    # before -> after table of OUT/KIND_BEFORE and OUT/KIND_AFTER with the bound's
    # and the misfit's columns, into OUT/NAME.md, docs/PROCEDURES.md between its
    # NAME markers and stdout.
    import sys
    out, before, after, name, lead, kinds = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6:]
    table = "\n".join(before_after_table(out, kinds, before, after, lead, [BOUND_COLUMN, MISFIT_COLUMN])) + "\n"
    open(f"{out}/{name}.md", "w").write(table)
    write_between_markers("docs/PROCEDURES.md", name, table)
    print(table)
