"""Parameter sweeps of scenes on dask: ``snail sweep``."""
