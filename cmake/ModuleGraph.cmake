# The module graph: written here once. CMake links each module to the modules it may use
# (cmake/ParallaxModule.cmake), the module_dependencies test checks every #include against it
# (cmake/CheckModuleDependencies.cmake), and the module_graph_docs test checks that the table in
# docs/architecture.md says the same. Every edge is there for a reason, given beside it.

# Modules in dependency order: each may use only modules listed before it.
set(PARALLAX_MODULES core image display scene io importer accel camera render sim quality layers window video cluster vision photomaker photocal jobs app python)

set(PARALLAX_USES_core "")
set(PARALLAX_USES_image core)
set(PARALLAX_USES_display core image)          # image: the mask layer's raster
set(PARALLAX_USES_scene core image)            # image: textures
set(PARALLAX_USES_io core image display scene) # reads and writes all three
# importer: scene files and the meshes they place (the readers, assimp's child process)
set(PARALLAX_USES_importer core image scene io)  # io: files, images (textures), JSON
set(PARALLAX_USES_accel core scene)            # builds Embree's scene from the Scene
set(PARALLAX_USES_camera core display scene)   # display rays, placed by the scene's placement
set(PARALLAX_USES_render core image display scene accel camera)  # traces cameras' rays
set(PARALLAX_USES_sim core image display)      # sees layers through a display's optics
set(PARALLAX_USES_quality core image display scene accel camera render sim)  # ideal vs seen
set(PARALLAX_USES_layers core image display scene accel camera render sim quality)  # fits layers to ideal views
set(PARALLAX_USES_window core image)           # shows Images on monitors
set(PARALLAX_USES_video core image)            # encodes Images as video (FFmpeg)
set(PARALLAX_USES_cluster core)               # the processes of one job (MPI)
set(PARALLAX_USES_vision core image)          # photos: decoding, markers, camera fit (OpenCV)
# photomaker: photos of physical panels from the physics alone, the truth calibration is tested
# against; deliberately apart from display, sim and the estimator (docs/calibration.md)
set(PARALLAX_USES_photomaker core image)
set(PARALLAX_USES_photocal core image display vision)  # shots and the estimator from photos
# jobs: the request layer under both front ends: typed requests, their checks and estimates, and
# one runner per use case (docs/architecture.md, "Requests")
set(PARALLAX_USES_jobs core image display scene io importer accel camera render sim quality layers video cluster vision photomaker photocal)
set(PARALLAX_USES_app core image display scene io importer accel camera render sim quality layers window video cluster vision photomaker photocal jobs)
# python: a peer of app on the request layer (jobs), never on app
set(PARALLAX_USES_python core image display scene io importer accel camera render sim quality vision photomaker photocal jobs)

# Third-party include prefixes and the one module that may use each (only in its .cpp files).
set(PARALLAX_THIRD_PARTY embree3 embree4 tbb nlohmann tiny_obj_loader tiny_gltf stb zlib assimp CLI SDL2
  libavcodec libavformat libavutil libswscale pybind11 mpi opencv2)
set(PARALLAX_OWNER_embree3 accel)  # Embree 3 (Debian 12) or
set(PARALLAX_OWNER_embree4 accel)  # Embree 4 (Debian 13), whichever is installed
set(PARALLAX_OWNER_tbb core)   # behind core/parallel.h
set(PARALLAX_OWNER_nlohmann io)
set(PARALLAX_OWNER_tiny_obj_loader importer)
set(PARALLAX_OWNER_tiny_gltf importer)
set(PARALLAX_OWNER_stb io)
set(PARALLAX_OWNER_zlib io)    # the PNG encoder's deflate
set(PARALLAX_OWNER_assimp importer)  # the long tail of mesh formats (importer/mesh_assimp.cpp)
set(PARALLAX_OWNER_CLI app)
set(PARALLAX_OWNER_SDL2 window)
set(PARALLAX_OWNER_libavcodec video)  # FFmpeg: encoders and decoders
set(PARALLAX_OWNER_libavformat video) # containers (MP4, WebM, Matroska)
set(PARALLAX_OWNER_libavutil video)
set(PARALLAX_OWNER_libswscale video)  # RGB <-> YUV 4:2:0
set(PARALLAX_OWNER_pybind11 python)  # the Python module (docs/python.md)
set(PARALLAX_OWNER_mpi cluster)       # Open MPI, only when launched by mpirun
set(PARALLAX_OWNER_opencv2 vision)    # OpenCV: photo decoding, ArUco markers, camera calibration
