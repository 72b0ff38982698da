pub mod budget;
pub mod command_stream;
