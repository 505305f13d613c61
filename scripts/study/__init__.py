"""The paper's studies: the scenes of xml/studies/ and their overrides (scenes), the kept runs in results/
(archive), one run as a workflow job (single_run, with app and progress), how a run stands (runs), the tables
(tables, with the paper's values in paper-values.csv) and the figures (figures). scripts/run-study.py is the command
line, scripts/workflow/Snakefile the workflow."""
