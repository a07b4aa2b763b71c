# Checks that the object files of the drivers' real-time part (mrqp_drivers_rt) reference no
# allocation, exception, lock or stdio function: the cyclic path cannot allocate, throw, block
# on a mutex or print, whatever the inputs.
#   cmake -DNM=<nm> -DOBJECTS="<a.o>|<b.o>|..." -P check_rt_symbols.cmake
string(REPLACE "|" ";" objects "${OBJECTS}")
set(forbidden
  "^malloc$" "^calloc$" "^realloc$" "^posix_memalign$" "^aligned_alloc$" "^memalign$"
  "^_Znwm" "^_Znam"                                   # operator new, new[]
  "^__cxa_allocate_exception$" "^__cxa_throw$" "^__cxa_rethrow$"
  "^_ZSt[0-9]+__throw_"                               # std::__throw_length_error, ... (containers)
  "^__cxa_guard_acquire$"                             # function-local statics (a lock)
  "^pthread_mutex_" "^pthread_rwlock_" "^pthread_cond_" "^sem_wait$"
  "^printf$" "^fprintf$" "^puts$" "^fputs$" "^fwrite$" "^putchar$" "^perror$" "^__printf_chk$"
  "^__fprintf_chk$" "^_ZSt4cout$" "^_ZSt4cerr$" "^_ZSt4clog$" "^snprintf$" "^__snprintf_chk$"
  "^_ZNSt7__cxx1112basic_string")                     # std::string
set(failures "")
list(LENGTH objects n)
if(n EQUAL 0)
  message(FATAL_ERROR "no object files given")
endif()
foreach(obj IN LISTS objects)
  execute_process(COMMAND ${NM} -u ${obj} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm failed on ${obj}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    string(REGEX REPLACE "^U[ \t]+" "" sym "${line}")
    string(REGEX REPLACE "@.*$" "" sym "${sym}")
    if(sym STREQUAL "")
      continue()
    endif()
    foreach(pat IN LISTS forbidden)
      if(sym MATCHES "${pat}")
        get_filename_component(name ${obj} NAME)
        string(APPEND failures "  ${name}: ${sym}\n")
      endif()
    endforeach()
  endforeach()
endforeach()
if(NOT failures STREQUAL "")
  message(FATAL_ERROR "real-time objects reference forbidden functions:\n${failures}")
endif()
message(STATUS "${n} real-time object files: no allocation, exception, lock or stdio reference")
