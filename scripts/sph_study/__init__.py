"""The study tool behind scripts/study: convergence studies, speed-against-error reports and stability
matrices of the sph program (usage: scripts/study -h; the text is the docstring of cli.py).

    plan.py      study file (checked, normalised) -> runs: options, folder, command line
    execute.py   running the runs: up-to-date checks, run.json, failure reasons, core counting
    collect.py   run folders -> rows, results.csv
    orders.py    observed order, time to reach an error level, speed table (pure arithmetic)
    plots.py     matplotlib plots
    report.py    report.md and the outputs of a convergence study
    matrix.py    the stability matrix: cells, matrix.csv, matrix.md
    selftest.py  scripts/study --self-test
    cli.py       arguments and main
    common.py    the repository root, JSON files
Unit tests: cd scripts && /usr/bin/python3 -m unittest discover -s sph_study/tests -t .
"""
