"""sdgbehave's Python package for the datasets it writes: `sdgbehave.data`.

Training code imports it (`from sdgbehave import data`). Behavior scripts,
which run inside sdgbehave, see a different `sdgbehave` module: the script
API the executable embeds (docs/scripting.md); this package is for code
outside the run."""
