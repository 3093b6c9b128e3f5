# The targets of the sanitizer stages (sourced by tools/sanitize.sh, which
# builds and runs them, and bench/build_time.sh, which times their build).
# asan: the untrusted-input (mesh and asset readers, the original layer's
# decoders), server and client suites
# and every fuzz target;
# tsan: the server's concurrency suites, core_test (Deferred, DeferredSequence,
# ParallelFor) and stream_test (the decoder's set-up threads, subband by
# subband: 18 s under TSan); the server suites also decode with them.
asan_suites=(core_test mesh_test asset_test entropy_test stream_test wavelet_test metrics_test remesh_test
             server_test server_http_test server_ws_test client_test client_e2e_test
             reliability_test child_process_test server_region_test original_layer_test)
fuzz_targets=(ply_reader_fuzz obj_reader_fuzz off_reader_fuzz container_fuzz packet_fuzz
              decoder_order_fuzz stream_header_fuzz http_request_fuzz ws_message_fuzz
              stream_splitter_fuzz ws_server_message_fuzz local_state_fuzz region_fuzz
              stream_units_fuzz gltf_asset_fuzz obj_asset_fuzz image_decoder_fuzz
              multipart_form_fuzz original_connectivity_fuzz original_positions_fuzz)
# Left out of the ASan stage for time (about 2.5 minutes of its 10 on two
# cores): long runs of the remesh, fidelity and metrics code on the shared
# meshes. Shorter tests of the same suites run that code under ASan; these
# run in the Release stage.
# Left to the Release stage: long remesh and fidelity runs, the original
# layer's round trip of every shared mesh (its decoders are fuzzed here), and the
# thread-count determinism runs (millions of samples or a remesh, three
# times over; the same code runs under ASan in the smaller tests, and
# races are TSan's), 10-60 s each under ASan.
asan_excluded_tests=(ClientE2eTest.TruePsnrWithAReference OriginalLayerStreamTest.EverySharedMeshComesBackWhole TangentStepTest.EstimatedPsnrTracksTheSurfacePsnr
                     RemeshTest.LeavesFewFlippedFacesOnAThinBentPlate RemeshTest.LeavesNoFlippedFaceOnSharedMeshes
                     IngestSqliteTest.RemeshesIrregularInput SharedMeshesTransformTest.PerfectReconstructionOnEveryBaseMesh
                     FidelityTest.ARemeshShortOfTheFidelityIsRedoneDenser ServerHttpTest.UploadWithAFidelityReachesIt
                     SurfaceDistanceTest.ThreadCountDoesNotChangeTheResult
                     PipelineThreadsTest.ARemeshedMeshGivesTheSameContainerOnAnyThreadCount
                     RemeshTest.GivesTheSameResultForAnyThreadCount FidelityTest.TheDensityLimitHolds
                     TangentStepTest.RdPrefixesAreCloserToTheSurfaceAtEqualBytes)
tsan_suites=(core_test stream_test server_http_test server_ws_test reliability_test)
