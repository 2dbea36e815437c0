"""The engine's render revision: a number raised whenever a node gives other pixels for the same
parameters (a generator's look, a filter's formula).

The selection models (sample banks, parameter predictors) are built from renders, so their
staleness key includes it (``selection.bank.graph_hash``): after an engine change, the shipped
models and those of a user library built by an older version are rebuilt instead of ranking
photos against descriptors of looks the engine no longer draws. The shipped banks are checked
against fresh renders by ``tests/pipeline/test_selection.py``, which fails when the looks moved
without this number and the models following.
"""

RENDER_REVISION = 8
