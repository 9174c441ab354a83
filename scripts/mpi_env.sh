# Open MPI refuses root and more ranks than cores unless told: CI runs as
# root on 2 cores. Sourced by run.sh, test.sh and the benchmark drivers.
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
# One thread per rank: two ranks on two cores must not oversubscribe.
export OMP_NUM_THREADS=1
export DEAL_II_NUM_THREADS=1
