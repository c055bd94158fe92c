// open_beneath.hpp - opening a file that a scene names, without leaving the
// scene's folder.
//
// A scene is untrusted and may come from elsewhere; the files it names must
// be the ones in its own folder or below it. Refusing ".." and absolute
// paths (the scene parser does) is not enough: a link (models/x.obj ->
// /etc/passwd, or a models/ folder that is itself a link) leads anywhere.
// So the path is walked one component at a time beneath an open descriptor
// of the folder, each with O_NOFOLLOW: a symbolic link at any component is
// refused, wherever it points, and nothing is looked up again by name.
#pragma once
#include <string>

namespace clrt {

// A descriptor of `relative` (components that are not "", "." or "..";
// no leading '/') opened read-only beneath the directory `root_fd`, never
// blocking on a FIFO (O_NONBLOCK; the caller refuses what is not a regular
// file). -1 with `why` set ("is a symbolic link", the system's reason, ...)
// otherwise; `why` names the component at fault when it is not the last.
int open_beneath(int root_fd, const std::string& relative, std::string& why);

}  // namespace clrt
