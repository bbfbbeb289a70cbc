// Test fixture, included by syntax_error_main.comp.

void broken() {
  float a = 1.0;
  float b = ) 2.0;
}
