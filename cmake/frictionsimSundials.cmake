# Select the imported SUNDIALS targets that frictionsim::sundials links, after find_package(SUNDIALS CONFIG).
#
#   SUNDIALS 6.x (Debian bookworm: 6.4): SUNDIALS::cvode_shared / SUNDIALS::cvode_static, ...
#                                         (SUNDIALS::cvode is an alias of the _shared one)
#   SUNDIALS 7.x:                         the same suffixed targets plus SUNDIALS::core_*, and SUNDIALS::cvode,
#                                         SUNDIALS::core, ... as aliases of whichever kind was built
#
# FRICTIONSIM_SUNDIALS_STATIC=ON requires the *_static targets (the Python extension links them so the wheel
# carries no SUNDIALS shared library); OFF prefers *_shared, then the unsuffixed name, then *_static; AUTO
# is ON where SUNDIALS::cvode_static exists and OFF otherwise (what `pip install .` uses).
function(frictionsim_sundials_libraries out_var)
    set(FRICTIONSIM_SUNDIALS_STATIC ${FRICTIONSIM_SUNDIALS_STATIC})  # function-local copy, AUTO resolved
    if(FRICTIONSIM_SUNDIALS_STATIC STREQUAL "AUTO")
        if(TARGET SUNDIALS::cvode_static)
            set(FRICTIONSIM_SUNDIALS_STATIC ON)
        else()
            set(FRICTIONSIM_SUNDIALS_STATIC OFF)
        endif()
        message(STATUS "frictionsim: FRICTIONSIM_SUNDIALS_STATIC=AUTO -> ${FRICTIONSIM_SUNDIALS_STATIC}")
    endif()
    # cvode first: with static archives it resolves the symbols it also bundles (6.x ships the serial
    # N_Vector, dense matrix and solvers inside libsundials_cvode), so the later archives add nothing twice.
    set(_required cvode)
    set(_optional nvecserial sunmatrixdense sunlinsoldense sunnonlinsolnewton sunnonlinsolfixedpoint core)
    set(_libs "")
    foreach(_component IN LISTS _required _optional)
        if(FRICTIONSIM_SUNDIALS_STATIC)
            set(_candidates SUNDIALS::${_component}_static)
        else()
            set(_candidates SUNDIALS::${_component}_shared SUNDIALS::${_component} SUNDIALS::${_component}_static)
        endif()
        set(_chosen "")
        foreach(_candidate IN LISTS _candidates)
            if(TARGET ${_candidate})
                set(_chosen ${_candidate})
                break()
            endif()
        endforeach()
        if(_chosen)
            list(APPEND _libs ${_chosen})
        elseif(_component IN_LIST _required)
            message(FATAL_ERROR
                "frictionsim: SUNDIALS ${SUNDIALS_VERSION} (${SUNDIALS_DIR}) has none of the targets "
                "${_candidates}. Install CVODE (Debian: libsundials-dev), or set "
                "FRICTIONSIM_SUNDIALS_STATIC=OFF if only shared libraries are installed.")
        endif()
    endforeach()
    if(FRICTIONSIM_SUNDIALS_STATIC)
        _frictionsim_sundials_static_closure("${_libs}")
    endif()
    set(${out_var} ${_libs} PARENT_SCOPE)
endfunction()

# SUNDIALS 6.4's export links some *_static targets to *_shared ones (SUNDIALS::sunlinsoldense_static ->
# SUNDIALS::sunmatrixdense_shared), which would put a shared SUNDIALS library back into a "static" link.
# Point such links at the *_static twin, for this build only (installed consumers see SUNDIALS unchanged).
function(_frictionsim_sundials_static_closure targets)
    set(_todo ${targets})
    set(_seen "")
    while(_todo)
        list(POP_FRONT _todo _target)
        if(_target IN_LIST _seen OR NOT TARGET ${_target})
            continue()
        endif()
        list(APPEND _seen ${_target})
        get_target_property(_links ${_target} INTERFACE_LINK_LIBRARIES)
        if(NOT _links)
            continue()
        endif()
        set(_fixed "")
        foreach(_link IN LISTS _links)
            if(_link MATCHES "^SUNDIALS::(.+)_shared$")
                if(TARGET SUNDIALS::${CMAKE_MATCH_1}_static)
                    set(_link SUNDIALS::${CMAKE_MATCH_1}_static)
                endif()
            endif()
            list(APPEND _fixed "${_link}")
            if(_link MATCHES "^SUNDIALS::")
                list(APPEND _todo ${_link})
            endif()
        endforeach()
        if(NOT _fixed STREQUAL _links)
            message(STATUS "frictionsim: ${_target} links ${_links}; using ${_fixed}")
            set_property(TARGET ${_target} PROPERTY INTERFACE_LINK_LIBRARIES "${_fixed}")
        endif()
    endwhile()
endfunction()
