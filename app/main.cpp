// ghostspace: maps the application's result to an exit code; all work is in gs_app.
#include "app/application.hpp"

int main(int argc, char** argv) {
  return gs::app::run(argc, argv);
}
