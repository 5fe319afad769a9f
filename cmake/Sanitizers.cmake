# AddressSanitizer + UndefinedBehaviorSanitizer for the CI's second pass (STIFFPATH_SANITIZE=ON).
if(STIFFPATH_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
