// Copyright (c) 2026 Aniso_conformal developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Test helpers for error messages, shared by the modules that check what a refusal says (test_io,
// test_repair, test_remesh). Include after <boost/test/unit_test.hpp>.

#ifndef ANISO_CONFORMAL_TEST_MESSAGE_CHECKS_H
#define ANISO_CONFORMAL_TEST_MESSAGE_CHECKS_H

#include <Aniso_conformal/Exceptions.h>

#include <functional>
#include <string>

namespace test {

// the message of the Invalid_input that `f` throws, "(no Invalid_input)" if it throws none
inline std::string message_of(const std::function<void()>& f)
{
  try { f(); } catch(const Aniso_conformal::Invalid_input& e) { return e.what(); }
  return "(no Invalid_input)";
}

// `true` if `s` contains `part`; when not, the test log says what was missing
inline bool contains(const std::string& s, const std::string& part)
{
  if(s.find(part) != std::string::npos) return true;
  BOOST_TEST_MESSAGE("'" << s << "' does not contain '" << part << "'");
  return false;
}

} // namespace test

#endif // ANISO_CONFORMAL_TEST_MESSAGE_CHECKS_H
