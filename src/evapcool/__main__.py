"""`python -m evapcool`, the same as the `evapcool` command."""

from evapcool.cli import main

raise SystemExit(main())
