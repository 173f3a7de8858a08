# source from the repo root:  source .dev/env.sh
# Open MPI 4.1.4 (Debian build, installed by .dev/install.sh) under gVisor, as root, single node.
export OMPI_ALLOW_RUN_AS_ROOT=1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none   # gVisor: no CMA / process_vm_readv
export OMPI_MCA_rmaps_base_oversubscribe=1             # -n 16 on fewer cores
export OMPI_MCA_hwloc_base_binding_policy=none
export OMPI_MCA_plm=isolated                           # single node: never look for ssh/rsh
export OMPI_MCA_pml=ob1                                # shared-memory path only, no UCX/OFI/PSM probing
export OMPI_MCA_btl=self,vader
export OMPI_MCA_oob_tcp_if_include=lo                  # no network: ORTE out-of-band over loopback
export OMPI_MCA_btl_base_warn_component_unused=0
export PMIX_MCA_gds=hash                               # avoid PMIx shared-memory datastore in containers
export OMP_NUM_THREADS=1
