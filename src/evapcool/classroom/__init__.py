"""The class competition: the `evapcool class` server, its store and verifier, `evapcool verify`.

Nothing here imports the server's extra (starlette, uvicorn, segno) at package import.
"""
