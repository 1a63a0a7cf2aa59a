"""`evapcool optimize`: the best evaporation strategy for the game (Optuna on Dask).

Needs the optional extra: pip install 'evapcool[cluster]'. Importing this package is
cheap; optuna, dask and pandas are imported only when a search runs.
"""
