# The module folders, lowest first; dependencies flow one way (docs/architecture.md).
set(RPSD_MODULES build_info config output linalg integrators substructure setups realtime transport operator_commands opensees servo node compensation ground_motion coordinator hdf5_output telemetry hybrid_test studies site_server scenarios commands monitor)
