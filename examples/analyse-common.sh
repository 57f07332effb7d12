# Sourced by examples/*/analyse.sh: python/activegrain on the path, figures without a display, and
# ag, which runs the package with Debian's python3 (the one that sees python3-mdanalysis and -ase).
# DT: the run's time step (the deck's default, or what -var dt gave it), for times in seconds.
examples_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export PYTHONPATH="$examples_dir/../python${PYTHONPATH:+:$PYTHONPATH}" MPLBACKEND=Agg
ag() { /usr/bin/python3 -m activegrain "$@"; }
timestep=${DT:-1.0e-4}
