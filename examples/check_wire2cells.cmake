# Command-line checks of the main job, run as `cmake -DWIRE2CELLS=<exe> -DDATA_DIR=<examples/data>
# -DWORK_DIR=<scratch> -DCASE=<case> -P check_wire2cells.cmake` (examples/CMakeLists.txt
# registers one CTest entry per case). Each case starts from an empty WORK_DIR/CASE folder
# holding a copy of the bundled wireframe named wire.obj; no shell, no stdin.
foreach(var WIRE2CELLS DATA_DIR WORK_DIR CASE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_wire2cells: -D${var}=... is required")
  endif()
endforeach()

set(dir "${WORK_DIR}/${CASE}")
file(REMOVE_RECURSE "${dir}")
file(MAKE_DIRECTORY "${dir}")
file(COPY_FILE "${DATA_DIR}/stepped_block.obj" "${dir}/wire.obj")
file(SHA256 "${DATA_DIR}/stepped_block.obj" input_hash)

# Runs wire2cells with the given arguments in ${dir}; sets rc, out and err.
function(run)
  execute_process(COMMAND "${WIRE2CELLS}" ${ARGN} WORKING_DIRECTORY "${dir}" RESULT_VARIABLE code
                  OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  set(rc "${code}" PARENT_SCOPE)
  set(out "${stdout}" PARENT_SCOPE)
  set(err "${stderr}" PARENT_SCOPE)
endfunction()

function(expect_exit code)
  if(NOT rc STREQUAL "${code}")
    message(FATAL_ERROR "expected exit status ${code}, got '${rc}'\nstdout:\n${out}\nstderr:\n${err}")
  endif()
endfunction()

function(expect_in text what)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected '${what}' in:\n${text}")
  endif()
endfunction()

function(expect_input_untouched)
  file(SHA256 "${dir}/wire.obj" hash)
  if(NOT hash STREQUAL input_hash)
    message(FATAL_ERROR "the input wire.obj was changed")
  endif()
endfunction()

if(CASE STREQUAL "help")
  run(--help)
  expect_exit(0)
  foreach(option -h --help -o --output --no-svg --format --tracer --merge-tolerance --planarity --strict
                 --reading --merge-unforced --keep-dangling --budget)
    expect_in("${out}" " ${option}")
  endforeach()
  foreach(word "usage: wire2cells" "exit status" ".3dcl" ".obj" ".ply" ".svg" ".step" "  4  read, but not a closed solid")
    expect_in("${out}" "${word}")
  endforeach()

elseif(CASE STREQUAL "outputs")
  # The four files land in ./out/; the input stays byte for byte what it was.
  run(wire.obj)
  expect_exit(0)
  foreach(ext 3dcl obj ply svg)
    if(NOT EXISTS "${dir}/out/wire.${ext}")
      message(FATAL_ERROR "out/wire.${ext} was not written\n${out}")
    endif()
    file(SIZE "${dir}/out/wire.${ext}" size)
    if(size EQUAL 0)
      message(FATAL_ERROR "out/wire.${ext} is empty")
    endif()
  endforeach()
  file(READ "${dir}/out/wire.3dcl" cells LIMIT 7)
  expect_in("${cells}" "3dcl 1")
  expect_in("${out}" "status: solid (a closed solid: 4 volumes")
  expect_input_untouched()
  # A plain edge list (a unit cube) into a folder given with -o, without the picture.
  file(WRITE "${dir}/cube.edges" "vertices 8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                 "edges 12\n0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n")
  # A house (a cube with a pyramid roof): the square under the roof is no face by default,
  # a wall between two volumes with --reading keep-walls.
  file(WRITE "${dir}/house.edges"
       "vertices 9\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 1.6\n"
       "edges 16\n0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n4 8\n5 8\n6 8\n7 8\n")
  run(--no-svg -o house_out house.edges)
  expect_exit(0)
  expect_in("${out}" "9 faces, 1 volumes")
  expect_in("${out}" "not a face: a 4-gon")
  run(--no-svg --reading keep-walls -o house_out house.edges)
  expect_exit(0)
  expect_in("${out}" "10 faces, 2 volumes")
  run(--no-svg --tracer seed -o cube_out cube.edges)
  expect_exit(0)
  expect_in("${out}" "6 faces, 1 volumes")
  if(NOT EXISTS "${dir}/cube_out/cube.3dcl" OR EXISTS "${dir}/cube_out/cube.svg")
    message(FATAL_ERROR "--no-svg -o cube_out: expected cube.3dcl and no cube.svg in cube_out/")
  endif()
  # A mesh OBJ (faces, no lines), its extension in capitals: the faces' edges are the wireframe.
  file(WRITE "${dir}/mesh.OBJ" "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")
  run(--no-svg -o mesh_out mesh.OBJ)
  expect_exit(0)
  expect_in("${out}" "8 vertices, 12 edges, 6 faces, 1 volumes")
  # --format step: the STEP file alone, a solid per volume (the stepped block has 4).
  run(--format step -o step_out wire.obj)
  expect_exit(0)
  file(GLOB written RELATIVE "${dir}/step_out" "${dir}/step_out/*")
  if(NOT written STREQUAL "wire.step")
    message(FATAL_ERROR "--format step: expected wire.step alone in step_out/, found '${written}'")
  endif()
  file(READ "${dir}/step_out/wire.step" step)
  expect_in("${step}" "ISO-10303-21;")
  expect_in("${step}" "AUTOMOTIVE_DESIGN")
  string(REGEX MATCHALL "=MANIFOLD_SOLID_BREP\\(" solids "${step}")
  list(LENGTH solids n)
  if(NOT n EQUAL 4)
    message(FATAL_ERROR "--format step: ${n} MANIFOLD_SOLID_BREPs in wire.step, expected 4")
  endif()
  run(--format step,3dcl,all -o all_out wire.obj)
  expect_exit(0)
  foreach(ext 3dcl obj ply svg step)
    if(NOT EXISTS "${dir}/all_out/wire.${ext}")
      message(FATAL_ERROR "--format all: out/wire.${ext} was not written\n${out}")
    endif()
  endforeach()

elseif(CASE STREQUAL "not_solid")
  # An open box (a floor and two walls): read, written, but not a closed solid: exit 4, the
  # reason on stderr and the files there to look at. A cube next to it: a solid, exit 0.
  file(WRITE "${dir}/open_box.edges" "vertices 8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n0 1 1\n1 0 1\n1 1 1\n"
                                     "edges 10\n0 1\n1 2\n2 3\n3 0\n0 4\n3 5\n4 5\n1 6\n2 7\n6 7\n")
  run(--no-svg open_box.edges)
  expect_exit(4)
  expect_in("${out}" "status: not a solid (an open surface: 8 edges lie on one face only)")
  expect_in("${err}" "read, but not a closed solid: an open surface")
  expect_in("${err}" "the files are written")
  if(NOT EXISTS "${dir}/out/open_box.3dcl")
    message(FATAL_ERROR "out/open_box.3dcl was not written for a result that is not a solid")
  endif()
  # A cube with a stick through its top: the stick pierces the face it ends in.
  file(WRITE "${dir}/stick.edges" "vertices 10\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                  "0.5 0.5 0.5\n0.5 0.5 2\n"
                                  "edges 13\n0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n8 9\n")
  run(--no-svg stick.edges)
  expect_exit(4)
  expect_in("${out}" "input edge 12 pierces face")
  file(WRITE "${dir}/cube.edges" "vertices 8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                 "edges 12\n0 1\n1 2\n2 3\n3 0\n4 5\n5 6\n6 7\n7 4\n0 4\n1 5\n2 6\n3 7\n")
  run(--no-svg cube.edges)
  expect_exit(0)
  expect_in("${out}" "status: solid (a closed solid: 1 volume, 6 faces")

elseif(CASE STREQUAL "budget")
  # A stage out of its work budget: status budget, the message naming the option on stderr,
  # exit 4 and nothing written (no face was read).
  run(--no-svg --budget 10 wire.obj)
  expect_exit(4)
  expect_in("${out}" "status: budget (trace_circuits: work budget of 10 steps exhausted")
  expect_in("${err}" "wire2cells: not read: trace_circuits: work budget of 10 steps exhausted; raise trace_options::work_budget")
  if(EXISTS "${dir}/out")
    message(FATAL_ERROR "out/ was made although the budget stopped the reading before any face")
  endif()
  expect_input_untouched()

elseif(CASE STREQUAL "overwrite")
  # An output named like the input in the input's folder: refused before anything is written.
  foreach(folder . "${dir}" "${dir}/../${CASE}")
    run(-o "${folder}" wire.obj)
    expect_exit(3)
    expect_in("${err}" "wire.obj")
    expect_input_untouched()
    foreach(ext 3dcl ply svg)
      if(EXISTS "${dir}/wire.${ext}")
        message(FATAL_ERROR "-o ${folder}: wire.${ext} was written although the run was refused")
      endif()
    endforeach()
  endforeach()

elseif(CASE STREQUAL "unwritable")
  # The output folder cannot be created (a file is in the way): an output error.
  run(-o wire.obj/sub wire.obj)
  expect_exit(3)
  expect_in("${err}" "wire.obj/sub")
  expect_input_untouched()

elseif(CASE STREQUAL "usage")
  run(--no-such-option wire.obj)
  expect_exit(2)
  expect_in("${err}" "--no-such-option")
  foreach(bad "--planarity;abc" "--merge-tolerance;-1" "--budget;1.5" "--tracer;dfs" "--reading;plugs" "--output"
              "--format;stl" "--format;")
    run(${bad})
    expect_exit(2)
    list(GET bad 0 option)
    expect_in("${err}" "${option}")
  endforeach()
  run(--jobs 0 wire.obj other.obj)
  expect_exit(2)
  expect_in("${err}" "--jobs")
  if(EXISTS "${dir}/out")
    message(FATAL_ERROR "a usage error created the output folder")
  endif()

elseif(CASE STREQUAL "missing_input")
  run(no_such_wireframe.obj)
  expect_exit(1)
  expect_in("${err}" "no_such_wireframe.obj")
  # A file that is not a wireframe: a parse error naming the file and line.
  file(WRITE "${dir}/broken.edges" "vertices 2\n0 0 0\n1 0 zero\n")
  run(broken.edges)
  expect_exit(1)
  expect_in("${err}" "broken.edges:3")

else()
  message(FATAL_ERROR "check_wire2cells: unknown CASE '${CASE}'")
endif()
