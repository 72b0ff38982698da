pub mod command_stream;
