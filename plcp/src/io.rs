//! Reading and writing problems: plcp's JSON format and the Siconos `.dat` format.
