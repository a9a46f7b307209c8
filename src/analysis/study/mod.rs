//! Studies of a turned thread, above the processes: the correction after measuring a part
//! (`correct`), the capability over the scatter (`capability`), the infeeds compared
//! (`compare`), a bolt and a nut assembled (`fit`) and the catalogue swept (`sweep`).

pub mod capability;
pub mod compare;
pub mod correct;
pub mod fit;
pub mod sweep;
