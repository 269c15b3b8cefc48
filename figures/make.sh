#!/usr/bin/env sh
# Regenerate every committed figure of README and docs/ from the shipped exercises:  sh figures/make.sh
# (needs cairosvg for the PNGs: pip install ".[dev]"). The benchmark figures (bench_*) are
# written by `python -m benchmarks.run`.
set -eu
cd "$(dirname "$0")/.."
run() { python -m planmethod "$@"; }
for name in fourbar_coupler_point offset_slider_crank scotch_yoke screen_sixbar shaper_sixbar \
            slotted_crank_crosshead slotted_lever; do
    run solve "exercises/$name.toml" --svg "figures/$name" --png > /dev/null
done
run solve exercises/compressor_slider_crank.toml --svg figures/compressor --png > /dev/null
run sweep exercises/shaper_sixbar.toml --step 2 --plot figures/shaper_sixbar/sweep.png > /dev/null
for name in combined_force_slider_crank conveyor_sixbar fourbar_forces fourbar_study loaded_press_sixbar; do
    mkdir -p "figures/forces/$name"
    run solve "exercises/$name.toml" --svg "figures/forces/$name" --png \
        > "figures/forces/$name/solve.txt"
done
# `check` exits 1 when it flags rows of the paper's table, as it does here: that is its result
run check exercises/conveyor_sixbar.toml exercises/conveyor_sixbar_table2.csv \
    > figures/forces/conveyor_sixbar/check_table2.txt || [ $? -eq 1 ]
run sweep exercises/conveyor_sixbar.toml --forces --plot figures/forces/conveyor_sixbar/forces_sweep.png > /dev/null
run sweep exercises/fourbar_study.toml --forces --plot figures/forces/fourbar_study/forces_sweep.png > /dev/null
run study exercises/fourbar_study.toml --plot figures/forces/fourbar_study/study.png \
    --csv figures/forces/fourbar_study/study.csv > figures/forces/fourbar_study/study.txt
