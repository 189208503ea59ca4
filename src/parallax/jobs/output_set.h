// OutputSet: the transaction every command's output files go through (docs/inputs.md,
// "Outputs").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace parallax::jobs {

// A set of output files written into a folder DIR that may hold other files (docs/inputs.md,
// "Outputs"). The files are written into a hidden temporary folder inside DIR
// (DIR/.parallax-tmp-PID: created there, it takes DIR's group, setgid bit and default ACL, and
// its files are on DIR's file system); commit() then renames each file into DIR, in the order
// path() was first asked for it (the record, render.json, last), so that a reader sees a new
// record only with its files in place. DIR itself is never replaced: its mode, owner, group and
// ACL stay as they are.
//
// Only files parallax wrote are replaced: a name is ours when DIR/.parallax-outputs (the list
// commit() keeps) or DIR's render.json (a record whose /program is "parallax": /outputs and
// /frames) or index.json (calibration patterns) lists it. commit() refuses, before the first
// rename, a name held by a folder, a link, a special file or a file that is not ours
// (check() says the same before any work). Files of ours that the new set does not have (the
// image-2.png of an earlier rank-2 set) are removed: the new record no longer describes them.
//
// A commit is rolled forward: before the first rename, a marker listing the files is written in
// the temporary folder; a later OutputSet for DIR that finds a temporary folder of a process
// that no longer runs finishes its renames when the marker is there, and removes the folder
// when it is not. Without commit (an exception), the temporary folder is removed and DIR is as
// it was. Commits into one folder are serialised (flock on DIR).
//
// Create it only when everything has been read and computed: it makes DIR.
class OutputSet {
 public:
  explicit OutputSet(const std::string& dir);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Where to write `name` (a plain file name) now; `name` joins the set.
  std::string path(const std::string& name);
  // The folder as the user named it, for messages.
  const std::string& dir() const { return dir_; }
  void commit();

  // Before any work: refuses (InputError) a DIR that is a file or cannot be written (or whose
  // nearest existing ancestor cannot), and each of `names` that DIR holds as something commit()
  // would not replace.
  static void check(const std::string& dir, const std::vector<std::string>& names);

  // Tests only: called after each file commit() renames into DIR (1, 2, ...), so that a test
  // can stop a commit halfway as a kill would.
  static void setCommitHookForTests(void (*hook)(size_t renamed));

 private:
  std::string dir_, folder_, temporary_;
  std::vector<std::string> names_;
  bool committed_ = false;
};

}  // namespace parallax::jobs
