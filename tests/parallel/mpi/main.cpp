// GoogleTest inside MPI_Init / MPI_Finalize for the multi-rank tests (../mpi_main.hpp).
#include "../mpi_main.hpp"

int main(int argc, char** argv) { return cgdem::test::run_tests_on_ranks(argc, argv); }
