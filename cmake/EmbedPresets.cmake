# Writes a C++ source holding the text of every preset YAML, so `--preset NAME` works wherever
# the binary is. Called as: cmake -DOUT=file.cpp -DIN="a.yaml|b.yaml" -P EmbedPresets.cmake
set(body "// Generated from configs/*.yaml by cmake/EmbedPresets.cmake. Do not edit.\n")
string(APPEND body "#include \"aavio/io/presets.hpp\"\n\nnamespace aavio::io {\n\n")
string(APPEND body "const std::vector<EmbeddedPreset>& EmbeddedPresets() {\n")
string(APPEND body "  static const std::vector<EmbeddedPreset> presets = {\n")
string(REPLACE "|" ";" files "${IN}")
foreach(file IN LISTS files)
  get_filename_component(name "${file}" NAME_WE)
  file(READ "${file}" text)
  string(APPEND body "      {\"${name}\", R\"aavio_preset(${text})aavio_preset\"},\n")
endforeach()
string(APPEND body "  };\n  return presets;\n}\n\n}  // namespace aavio::io\n")
file(WRITE "${OUT}" "${body}")
