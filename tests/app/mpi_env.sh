# SPDX-License-Identifier: Apache-2.0
# Sourced by the command-line tests that run phasor on several MPI ranks (mpi.sh, checkpoint.sh,
# sweep.sh): PH, the command that runs phasor on $ranks ranks (1: phasor itself), and
# signal_job SIGNAL PID, which sends SIGNAL to that command's processes — the ranks themselves, as a
# batch system does (mpirun, given a signal, passes it on only after odls_base_sigkill_timeout;
# mpi.sh's `sigterm` part tests that path). Open MPI settings that work without a network, without
# ssh and as root in a container (docs/distributed.md "Running the tests"):
#   btl self,vader            shared memory between the ranks of this machine, no TCP
#   plm isolated              no ssh/rsh launcher: every rank on this machine
#   vader single copy none    no CMA/ptrace (refused in many containers)
#   --oversubscribe           more ranks than cores (-n 3 on 2 cores)
#   --allow-run-as-root       Open MPI refuses root otherwise (CI containers run as root)
export OMPI_MCA_btl=self,vader OMPI_MCA_plm=isolated OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1
ranks=${ranks:-1}
if [[ $ranks -gt 1 ]]; then
    PH=(mpirun -q --oversubscribe --allow-run-as-root -n "$ranks" "$phasor")
else
    PH=("$phasor")
fi
signal_job() {
    if [[ $ranks -gt 1 ]]; then pkill "-$1" -P "$2"; else kill "-$1" "$2"; fi
}
