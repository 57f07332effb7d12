"""How the integration tests start LAMMPS on several ranks."""
import os

MPIRUN = os.environ.get("ACTIVEGRAIN_MPIRUN", "mpirun")


def mpi_prefix(ranks):
    """The mpirun words before the lmp command for `ranks` ranks (none for 1): as root Open MPI
    needs --allow-run-as-root, and past 2 ranks on this 2-core machine --oversubscribe."""
    if ranks == 1:
        return []
    flags = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    if ranks > 2:
        flags.append("--oversubscribe")
    return [MPIRUN, *flags, "-np", str(ranks)]
