"""The class competition (issue 22): `evapcool verify` now; the `evapcool class` server later.

Nothing here imports the server's extra (starlette, uvicorn, segno) at package import.
"""
