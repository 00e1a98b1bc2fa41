#include <gtest/gtest.h>

#include <cstdlib>

#include "web/auth.hpp"
#include "web/config.hpp"
#include "web/url.hpp"

namespace fsd::web {
namespace {

TEST(Auth, TokenComparison) {
  EXPECT_TRUE(token_matches("abc123", "abc123"));
  EXPECT_FALSE(token_matches("abc124", "abc123"));
  EXPECT_FALSE(token_matches("abc12", "abc123"));
  EXPECT_FALSE(token_matches("abc1234", "abc123"));
  EXPECT_FALSE(token_matches("", "abc123"));
  EXPECT_FALSE(token_matches("", ""));  // no token configured: nobody is authorised
  EXPECT_FALSE(token_matches("x", ""));
}

TEST(Auth, BearerHeader) {
  EXPECT_EQ(bearer_token("Bearer abc"), "abc");
  EXPECT_EQ(bearer_token("bearer   abc  "), "abc");
  EXPECT_FALSE(bearer_token("Basic abc"));
  EXPECT_FALSE(bearer_token("Bearer "));
  EXPECT_FALSE(bearer_token(""));
}

TEST(Auth, OriginRules) {
  const std::vector<std::string> none;
  EXPECT_TRUE(origin_allowed("", "car:8080", none));  // programs send no Origin
  EXPECT_TRUE(origin_allowed("http://car:8080", "car:8080", none));
  EXPECT_TRUE(origin_allowed("http://CAR:8080", "car:8080", none));
  EXPECT_TRUE(origin_allowed("http://car", "car:80", none));
  EXPECT_FALSE(origin_allowed("http://car:8081", "car:8080", none));
  EXPECT_FALSE(origin_allowed("http://evil.example", "car:8080", none));
  EXPECT_FALSE(origin_allowed("null", "car:8080", none));
  EXPECT_FALSE(origin_allowed("http://car:8080/x", "car:8080", none));
  const std::vector<std::string> list{"https://app.foxglove.dev"};
  EXPECT_TRUE(origin_allowed("https://app.foxglove.dev", "car:8080", list));
  EXPECT_TRUE(origin_allowed("https://app.foxglove.dev:443", "car:8080", list));
  EXPECT_FALSE(origin_allowed("http://app.foxglove.dev", "car:8080", list));
  EXPECT_FALSE(origin_allowed("http://car:8080", "car:8080", list));  // a list replaces the same-host rule
  EXPECT_TRUE(origin_allowed("http://anything:1", "car:8080", {"*"}));
  EXPECT_EQ(split_list(" a, b ,,c "), (std::vector<std::string>{"a", "b", "c"}));
}

TEST(Auth, EnvironmentOverridesTheConfiguredToken) {
  WebConfig c;
  c.token = "from-config";
  ::unsetenv("FSD_WEB_TOKEN");
  EXPECT_EQ(effective_token(c), "from-config");
  ::setenv("FSD_WEB_TOKEN", "from-env", 1);
  EXPECT_EQ(effective_token(c), "from-env");
  ::setenv("FSD_WEB_TOKEN", "", 1);
  EXPECT_EQ(effective_token(c), "");  // set but empty disables tuning
  ::unsetenv("FSD_WEB_TOKEN");
}

TEST(Url, PercentDecoding) {
  EXPECT_EQ(percent_decode("/a%20b"), "/a b");
  EXPECT_EQ(percent_decode("%2e%2E"), "..");
  EXPECT_EQ(percent_decode("a+b"), "a+b");
  EXPECT_EQ(percent_decode("a+b", true), "a b");
  EXPECT_FALSE(percent_decode("%"));
  EXPECT_FALSE(percent_decode("%4"));
  EXPECT_FALSE(percent_decode("%zz"));
  EXPECT_FALSE(percent_decode("a%00b"));
}

TEST(Url, QueryParameters) {
  const auto t = split_target("/ws?x=1&token=a%2Bb%26c&y");
  EXPECT_EQ(t.path, "/ws");
  EXPECT_EQ(query_param(t.query, "token"), "a+b&c");
  EXPECT_EQ(query_param(t.query, "y"), "");
  EXPECT_FALSE(query_param(t.query, "z"));
  EXPECT_EQ(split_target("/plain").query, "");
}

}  // namespace
}  // namespace fsd::web
