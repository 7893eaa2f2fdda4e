"""The documentation's generated parts and pictures: made from the code, checked by a test.

README.md and docs/*.md are hand-written, except blocks between markers that app/docs/blocks.py
makes from the code: the key table (app.keys), the command-line options (the argparse parsers),
the scene catalogue (app.catalogue, what `--list --json` prints), the metrics each scene reports
and their units, the fields of a --json summary, the exercises and the benchmarks. The pictures in
docs/images/ are headless screenshots (app/docs/images.py). `python -m app.docs` rewrites the
blocks (`--check`: says which are stale; `--images`: remakes the pictures); tests/test_docs.py
fails when the checked-in docs differ from what the code generates.
"""
